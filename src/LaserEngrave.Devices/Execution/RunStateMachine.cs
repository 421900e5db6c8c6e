using LaserEngrave.Core.Jobs;

namespace LaserEngrave.Devices.Execution;

/// <summary>The run's states and the legal transitions between them, in one table.</summary>
/// <remarks>
/// <see cref="RunExecutor"/> moves only along this table; a request for any other transition (a pause that arrives
/// after the end, an abort that races the last move) is ignored. docs/execution.md draws the same table.
/// </remarks>
public static class RunStateMachine
{
    private static readonly Dictionary<RunState, RunState[]> Legal = new()
    {
        [RunState.Idle] = [RunState.Preflight, RunState.Aborting],
        [RunState.Preflight] = [RunState.Running, RunState.Aborting, RunState.Failed],

        // Running to Paused: a pause asked before the first move is taken at that move, without Pausing first.
        [RunState.Running] = [RunState.Pausing, RunState.Paused, RunState.Aborting, RunState.Completed, RunState.Failed],

        // Pausing to Completed: the pause was asked during the last move, so nothing is left to pause before.
        [RunState.Pausing] = [RunState.Paused, RunState.Running, RunState.Aborting, RunState.Completed, RunState.Failed],
        [RunState.Paused] = [RunState.Running, RunState.Aborting, RunState.Failed],

        // Aborting to Completed: the abort came after the last move had been done; the run is whole.
        [RunState.Aborting] = [RunState.Aborted, RunState.Completed],
        [RunState.Completed] = [],
        [RunState.Aborted] = [],
        [RunState.Failed] = [],
    };

    /// <summary>Whether a run may go from <paramref name="from"/> to <paramref name="to"/> (staying in a state is not a transition).</summary>
    public static bool IsLegal(RunState from, RunState to) => Legal.TryGetValue(from, out var next) && next.Contains(to);

    /// <summary>Whether <paramref name="state"/> ends a run: Completed, Aborted or Failed; nothing leaves it.</summary>
    public static bool IsEnd(RunState state) => state is RunState.Completed or RunState.Aborted or RunState.Failed;

    /// <summary>The states a run may go to from <paramref name="from"/>.</summary>
    public static IReadOnlyList<RunState> Next(RunState from) => Legal.TryGetValue(from, out var next) ? next : [];

    /// <summary>The end state of a run that ended with <paramref name="outcome"/>.</summary>
    public static RunState EndState(RunOutcome outcome) => outcome switch
    {
        RunOutcome.Completed => RunState.Completed,
        RunOutcome.Aborted => RunState.Aborted,
        _ => RunState.Failed,
    };
}
