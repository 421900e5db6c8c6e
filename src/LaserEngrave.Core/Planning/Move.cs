namespace LaserEngrave.Core.Planning;

/// <summary>What the laser does during a move.</summary>
public enum MoveKind : byte
{
    /// <summary>Laser off, at travel speed.</summary>
    Travel,

    /// <summary>Laser on, at burn speed, along X only.</summary>
    Burn,

    /// <summary>Laser off, at burn speed, along X: the run-up before or run-out after a burn run (overscan).</summary>
    Overscan,
}

/// <summary>One straight move of the stage between two absolute positions in whole microsteps.</summary>
/// <param name="Kind">Laser state and speed class of the move.</param>
/// <param name="X0">Start X, microsteps.</param>
/// <param name="Y0">Start Y, microsteps.</param>
/// <param name="X1">End X, microsteps.</param>
/// <param name="Y1">End Y, microsteps.</param>
/// <param name="Row">Image row the move belongs to (for a travel, the row it leads to).</param>
public readonly record struct Move(MoveKind Kind, long X0, long Y0, long X1, long Y1, int Row)
{
    public long LengthX => Math.Abs(X1 - X0);

    public long LengthY => Math.Abs(Y1 - Y0);
}
