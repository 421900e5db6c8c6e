namespace LaserEngrave.Core.Vectors;

/// <summary>How paths become strokes of the two axes (docs/vectors.md, "Smooth paths on two axes").</summary>
public sealed record VectorMotionOptions
{
    public static VectorMotionOptions Default { get; } = new();

    /// <summary>
    /// The largest distance of the planned motion from the path while the laser is on, µm: a stroke whose model goes
    /// further (at a sharp corner) is split there, the laser off and the stage stopping and starting again.
    /// </summary>
    /// <remarks>Kept below the 3 µm the twin must show, since the latencies' spread adds to it.</remarks>
    public double DeviationLimitUm { get; init; } = 1.0;

    /// <summary>Stop at every vertex with the laser off instead of moving on (for comparison: docs/vectors.md measures both).</summary>
    public bool StopAtEveryVertex { get; init; }
}
