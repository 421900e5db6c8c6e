using LaserEngrave.Core.Jobs;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>The run's transition table, every pair of states, against the table docs/execution.md draws.</summary>
public class RunStateMachineTests
{
    // Rows: from; columns: to, in the enum's order (Idle, Preflight, Running, Pausing, Paused, Aborting, Completed, Aborted, Failed).
    private static readonly string[] Expected =
    [
        "Idle      . x . . . x . . .",
        "Preflight . . x . . x . . x",
        "Running   . . . x x x x . x",
        "Pausing   . . x . x x x . x",
        "Paused    . . x . . x . . x",
        "Aborting  . . . . . . x x .",
        "Completed . . . . . . . . .",
        "Aborted   . . . . . . . . .",
        "Failed    . . . . . . . . .",
    ];

    public static TheoryData<RunState, RunState, bool> EveryPair()
    {
        var data = new TheoryData<RunState, RunState, bool>();
        var states = Enum.GetValues<RunState>();
        foreach (var row in Expected)
        {
            var cells = row.Split(' ', StringSplitOptions.RemoveEmptyEntries);
            var from = Enum.Parse<RunState>(cells[0]);
            for (var i = 0; i < states.Length; i++)
            {
                data.Add(from, states[i], cells[i + 1] == "x");
            }
        }

        return data;
    }

    [Theory]
    [MemberData(nameof(EveryPair))]
    public void IsLegal_EveryPairOfStates_MatchesTheTable(RunState from, RunState to, bool legal)
    {
        Assert.Equal(legal, RunStateMachine.IsLegal(from, to));
        Assert.Equal(legal, RunStateMachine.Next(from).Contains(to));
    }

    [Fact]
    public void Expected_CoversEveryState_InTheEnumsOrder()
    {
        Assert.Equal(Enum.GetValues<RunState>().Select(s => s.ToString()), Expected.Select(r => r.Split(' ')[0]));
    }

    [Theory]
    [InlineData(RunState.Completed, true)]
    [InlineData(RunState.Aborted, true)]
    [InlineData(RunState.Failed, true)]
    [InlineData(RunState.Idle, false)]
    [InlineData(RunState.Aborting, false)]
    [InlineData(RunState.Paused, false)]
    public void IsEnd_State_TrueOnlyForTheThreeEnds(RunState state, bool end)
    {
        Assert.Equal(end, RunStateMachine.IsEnd(state));
        Assert.Equal(end, RunStateMachine.Next(state).Count == 0);
    }

    [Theory]
    [InlineData(RunOutcome.Completed, RunState.Completed)]
    [InlineData(RunOutcome.Aborted, RunState.Aborted)]
    [InlineData(RunOutcome.Failed, RunState.Failed)]
    [InlineData(RunOutcome.Refused, RunState.Failed)]
    public void EndState_Outcome_IsTheStateTheRunEndsIn(RunOutcome outcome, RunState state)
    {
        Assert.Equal(state, RunStateMachine.EndState(outcome));
    }

    [Fact]
    public void EveryState_ReachableFromIdle_AndEveryRunCanEnd()
    {
        var reached = new HashSet<RunState> { RunState.Idle };
        var queue = new Queue<RunState>(reached);
        while (queue.TryDequeue(out var state))
        {
            foreach (var next in RunStateMachine.Next(state).Where(reached.Add))
            {
                queue.Enqueue(next);
            }
        }

        Assert.Equal(Enum.GetValues<RunState>().ToHashSet(), reached);
        Assert.All(Enum.GetValues<RunState>().Where(s => !RunStateMachine.IsEnd(s)), s => Assert.Contains(RunStateMachine.Next(s), n => n != s));
    }
}
