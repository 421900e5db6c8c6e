namespace LaserEngrave.Core.Planning;

/// <summary>A burn run of a stroke: the laser on from <see cref="OnX"/> to <see cref="OffX"/>.</summary>
/// <param name="Move">The plan's burn move (its start trimmed to the resume X on a run resumed midway).</param>
/// <param name="MoveIndex">Its index in the plan's moves.</param>
public readonly record struct BurnRun(Move Move, long MoveIndex)
{
    /// <summary>Absolute X of the switch-on edge, microsteps.</summary>
    public long OnX => Move.X0;

    /// <summary>Absolute X of the switch-off edge, microsteps.</summary>
    public long OffX => Move.X1;
}
