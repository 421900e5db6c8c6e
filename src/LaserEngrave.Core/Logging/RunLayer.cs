using LaserEngrave.Core.Jobs;

namespace LaserEngrave.Core.Logging;

/// <summary>One layer of a layered run, in the order it ran: what it burned, how, and how it ended.</summary>
/// <param name="Name">The layer's name in the job file.</param>
/// <param name="Source">The image or drawing file, full path.</param>
/// <param name="Sha256">SHA-256 of the file's bytes.</param>
/// <param name="Mode">Raster, outline, fill or both.</param>
/// <param name="DrawingLayer">The drawing's layer burned, or null for all of it.</param>
/// <param name="WidthMm">Width on the stage, mm.</param>
/// <param name="HeightMm">Height on the stage, mm.</param>
/// <param name="OriginXMm">Stage X of its top-left corner, mm.</param>
/// <param name="OriginYMm">Stage Y of its top-left corner, mm.</param>
/// <param name="BurnSpeedMmPerS">Its burn speed, mm/s.</param>
/// <param name="FrequencyHz">Its laser frequency, Hz.</param>
/// <param name="Passes">Passes asked for.</param>
public sealed record RunLayer(
    string Name,
    string Source,
    string Sha256,
    LayerMode Mode,
    string? DrawingLayer,
    double WidthMm,
    double HeightMm,
    double OriginXMm,
    double OriginYMm,
    double BurnSpeedMmPerS,
    double FrequencyHz,
    int Passes)
{
    /// <summary>Passes completed.</summary>
    public int PassesDone { get; init; }

    /// <summary>How its last pass ended; null when the layer never started (an earlier one stopped the run).</summary>
    public RunOutcome? Outcome { get; init; }

    /// <summary>Completed by the run this one resumed (`--resume`, the app's Continue), and not burned in this one.</summary>
    public bool CompletedBefore { get; init; }

    /// <summary>Its estimate, all passes, preflight and positioning included, s.</summary>
    public double EstimatedSeconds { get; init; }

    /// <summary>The engraving part of <see cref="EstimatedSeconds"/>, all passes, s.</summary>
    public double EstimatedEngravingSeconds { get; init; }

    /// <summary>The part of its time the estimate models, s.</summary>
    public double EngravingSeconds { get; init; }

    public double LaserOnSeconds { get; init; }

    /// <summary>On the simulator: the twin's check of this layer alone.</summary>
    public RunSimulation? Simulation { get; init; }
}
