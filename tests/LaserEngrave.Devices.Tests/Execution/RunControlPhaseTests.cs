using LaserEngrave.Devices.Execution;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>The run's phase, held once in its <see cref="RunControl"/> for the session and every pass's executor.</summary>
public class RunControlPhaseTests
{
    [Fact]
    public void Entered_PassesOneAfterTheOther_FollowsEachButNotTheirEnds()
    {
        var control = new RunControl();

        foreach (var state in new[] { RunState.Preflight, RunState.Running, RunState.Completed, RunState.Preflight, RunState.Running })
        {
            control.Entered(state);
        }

        Assert.Equal(RunState.Running, control.Phase);
        control.Entered(RunState.Failed);
        Assert.Equal(RunState.Running, control.Phase);
        control.End(RunState.Failed);
        Assert.Equal(RunState.Failed, control.Phase);
    }

    [Fact]
    public void RequestAbort_BetweenPasses_IsAbortingAtOnceAndTheNextPassCannotLeaveIt()
    {
        var control = new RunControl();
        control.Entered(RunState.Preflight);
        control.Entered(RunState.Running);
        control.Entered(RunState.Completed);

        control.RequestAbort();
        Assert.Equal(RunState.Aborting, control.Phase);

        control.Entered(RunState.Preflight);
        control.Entered(RunState.Running);
        Assert.Equal(RunState.Aborting, control.Phase);
        control.Entered(RunState.Aborting);
        control.Entered(RunState.Aborted);
        Assert.Equal(RunState.Aborting, control.Phase);
    }

    [Fact]
    public void RequestAbort_AfterTheRunEnded_LeavesTheEnd()
    {
        var control = new RunControl();
        control.Entered(RunState.Preflight);
        control.End(RunState.Completed);

        control.RequestAbort();
        control.Entered(RunState.Running);

        Assert.Equal(RunState.Completed, control.Phase);
    }

    [Fact(Timeout = 60_000)]
    public async Task EngraveSession_AbortBeforeTheFirstPass_ReadsAbortingFromTheControlAtOnce()
    {
        await using var run = SimulatedRun.Create();
        var job = TestJobs.FromMask(TestJobs.RandomMask(1, 8, 4), 1, new Core.Planning.PlanOptions());
        var session = new EngraveSession(new EngraveMachine(run.Stage, run.Gate, run.Time, "simulator", "simulator") { Simulated = true }, job);

        session.Abort();

        Assert.Equal(RunState.Aborting, session.State);
        Assert.Equal(RunState.Aborting, session.Progress.State);
    }
}
