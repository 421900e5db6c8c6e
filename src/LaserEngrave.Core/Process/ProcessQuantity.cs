namespace LaserEngrave.Core.Process;

/// <summary>The quantity a <see cref="ProcessQuery"/> solves for.</summary>
public enum ProcessQuantity
{
    Speed,
    Frequency,
    Spacing,
    PulsesPerDot,

    /// <summary>Everything was given and agrees: nothing to solve, only the figures.</summary>
    None,
}
