namespace LaserEngrave.Core.Planning;

/// <summary>How a mask is turned into moves.</summary>
public enum PlanStrategy
{
    /// <summary>
    /// Seed 000 as printed: every row (blank ones too), left to right, every run of white or black its own move,
    /// a travel back to each row's start, one speed (the burn speed) for all moves.
    /// </summary>
    Paper,

    /// <summary>
    /// Skip blank rows and leading and trailing white, one travel per white gap and per row change, serpentine rows
    /// when bidirectional, optional overscan around each burn run.
    /// </summary>
    Optimized,
}
