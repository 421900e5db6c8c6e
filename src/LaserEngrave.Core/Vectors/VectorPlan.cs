namespace LaserEngrave.Core.Vectors;

/// <summary>A drawing placed on the stage and ordered: the paths to burn, in order, in whole microsteps, with the figures of the job.</summary>
public sealed record VectorPlan
{
    public required string DrawingPath { get; init; }

    /// <summary>Every path in burn order: fill scan lines first (when filled), then the outlines.</summary>
    public required IReadOnlyList<StagePath> Paths { get; init; }

    /// <summary>The fill's scan lines as raster-like rows (empty when not filled).</summary>
    public required IReadOnlyList<FillRow> FillRows { get; init; }

    /// <summary>Where the travel is counted from: the drawing's top-left corner on the stage.</summary>
    public required StagePoint Start { get; init; }

    public required double MicrostepUm { get; init; }

    /// <summary>Millimetres on the stage per millimetre of the drawing (1 when the drawing's own units are kept).</summary>
    public required double Scale { get; init; }

    public required double WidthMm { get; init; }

    public required double HeightMm { get; init; }

    public required double ToleranceUm { get; init; }

    /// <summary>Length burned: every path's vertices, as rounded to microsteps, mm.</summary>
    public required double BurnLengthMm { get; init; }

    /// <summary>Laser-off travel from <see cref="Start"/> through the paths in burn order, mm.</summary>
    public required double TravelMm { get; init; }

    /// <summary>The same travel with the paths in drawing order, each as drawn, mm.</summary>
    public required double TravelDrawingOrderMm { get; init; }

    public required bool FitsTravel { get; init; }

    public required IReadOnlyList<string> Warnings { get; init; }

    /// <summary>How much shorter the travel is than in drawing order, percent.</summary>
    public double TravelSavedPercent => TravelDrawingOrderMm > 0 ? 100 * (TravelDrawingOrderMm - TravelMm) / TravelDrawingOrderMm : 0;

    public int OutlineCount => Paths.Count(p => p.Kind == VectorPathKind.Outline);
}
