using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Logging;

/// <summary>How a drawing was read, placed and ordered for a run, and its strokes (null in the log of an image).</summary>
/// <param name="ToleranceUm">Chord tolerance of the curves, µm.</param>
/// <param name="Fill">Outline, fill or both.</param>
/// <param name="FillPitchUm">Distance between fill scan lines, µm.</param>
/// <param name="DrawingOrder">Whether the paths were burned in the file's order (unoptimised).</param>
/// <param name="Scale">Millimetres on the stage per millimetre of the drawing.</param>
/// <param name="Paths">Paths burned (outlines and fill rows).</param>
/// <param name="Strokes">Strokes of the two axes (a path is split at corners too sharp to follow).</param>
/// <param name="BurnLengthMm">Length burned, mm.</param>
/// <param name="TravelMm">Laser-off travel between paths, mm.</param>
/// <param name="PredictedDeviationUm">The motion model's largest distance from the path with the laser on, µm.</param>
public sealed record RunDrawing(
    double ToleranceUm,
    VectorFillMode Fill,
    double FillPitchUm,
    bool DrawingOrder,
    double Scale,
    int Paths,
    int Strokes,
    double BurnLengthMm,
    double TravelMm,
    double PredictedDeviationUm)
{
    /// <summary>The drawing options that repeat the run (width and origin come from the log's geometry).</summary>
    public VectorOptions ToVectorOptions() => new()
    {
        ToleranceUm = ToleranceUm,
        Fill = Fill,
        FillPitchUm = FillPitchUm,
        Optimize = !DrawingOrder,
    };
}
