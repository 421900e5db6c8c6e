namespace LaserEngrave.Core.Planning;

/// <summary>One step of a raster program as <see cref="RasterProgram.Steps()"/> hands it out: a travel, a stroke or a plain move.</summary>
public readonly record struct RasterStep
{
    private RasterStep(StrokeStep? stroke, TravelStep travel, MoveStep move, bool isTravel)
    {
        Stroke = stroke;
        Travel = travel;
        Move = move;
        IsTravel = isTravel;
    }

    /// <summary>The stroke, when the step is one (it owns its buffers: kept after the next step is read).</summary>
    public StrokeStep? Stroke { get; }

    /// <summary>The travel, when <see cref="IsTravel"/>.</summary>
    public TravelStep Travel { get; }

    /// <summary>The plain move of a step-by-step program, when the step is neither a stroke nor a travel.</summary>
    public MoveStep Move { get; }

    public bool IsTravel { get; }

    /// <summary>The plan's first move of the step (the resume point's, trimmed, on a resumed run).</summary>
    public Move FirstMove => Stroke?.MoveAt(0) ?? (IsTravel ? Travel.Move : Move.Move);

    public static RasterStep Of(StrokeStep stroke) => new(stroke, default, default, false);

    public static RasterStep Of(in TravelStep travel) => new(null, travel, default, true);

    public static RasterStep Of(in MoveStep move) => new(null, default, move, false);
}
