using LaserEngrave.Core.Planning;

namespace LaserEngrave.Devices.Execution;

/// <summary>One move of the plan done (the stage arrived), so a view can draw what is burned so far.</summary>
/// <param name="Move">The move just completed.</param>
/// <param name="MoveIndex">Its index in <see cref="RasterPlan.Moves()"/>.</param>
public sealed class MoveCompletedEventArgs(Move move, long moveIndex) : EventArgs
{
    public Move Move { get; } = move;

    public long MoveIndex { get; } = moveIndex;
}

/// <summary>The run's state changed.</summary>
public sealed class RunStateChangedEventArgs(RunState previous, RunState state) : EventArgs
{
    public RunState Previous { get; } = previous;

    public RunState State { get; } = state;
}
