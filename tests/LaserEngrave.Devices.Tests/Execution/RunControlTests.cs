using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>Pause, resume, abort and progress of a run on the in-process simulator.</summary>
public class RunControlTests
{
    [Fact(Timeout = 120_000)]
    public async Task Pause_MidRun_StopsWithTheLaserOffAndResumeFinishesTheMask()
    {
        await using var run = SimulatedRun.Create();
        var job = TestJobs.FromMask(TestJobs.RandomMask(seed: 3, 16, 8), 1.2, new PlanOptions());
        var executor = run.Executor(job);
        var states = new List<RunState>();
        bool? firingWhilePaused = null;
        var completedWhilePaused = 0;
        var moves = 0;
        executor.MoveCompleted += (_, _) =>
        {
            if (++moves == 20)
            {
                executor.Pause();
            }

            if (executor.State == RunState.Paused)
            {
                completedWhilePaused++;
            }
        };
        executor.StateChanged += (_, e) =>
        {
            states.Add(e.State);
            if (e.State == RunState.Paused)
            {
                firingWhilePaused = run.Machine.Gate.IsFiring;
                _ = Task.Delay(TimeSpan.FromSeconds(5), run.Time).ContinueWith(_ => executor.Resume(), run.Loop);
            }
        };

        var result = await run.Do(() => executor.RunAsync(TestContext.Current.CancellationToken));

        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        Assert.Equal([RunState.Preflight, RunState.Running, RunState.Pausing, RunState.Paused, RunState.Running, RunState.Completed], states);
        Assert.False(firingWhilePaused);
        Assert.Equal(0, completedWhilePaused);
        Assert.True(run.Analyze(job).Burned.ContentEquals(job.Mask));
        Assert.True(result.Duration - result.EngravingDuration >= TimeSpan.FromSeconds(5), "the pause is counted as engraving time");
    }

    [Fact(Timeout = 120_000)]
    public async Task Abort_WhileBurning_SwitchesTheLaserOffBeforeStoppingTheStage()
    {
        await using var run = SimulatedRun.Create();
        var devices = new RecordingDevices(run.Stage, run.Gate);
        var job = TestJobs.FromMask(TestJobs.Mask("################", "################"), 4, new PlanOptions());
        var executor = new RunExecutor(devices.Stage, devices.Gate, job, run.Time);
        var aborted = 0;
        executor.ProgressChanged += (_, p) =>
        {
            if (p.LaserOn && p.State == RunState.Running && Interlocked.Exchange(ref aborted, 1) == 0)
            {
                // From another thread, part-way into the burn.
                _ = Task.Delay(TimeSpan.FromSeconds(1), run.Time).ContinueWith(_ => executor.Abort(), run.Loop);
            }
        };

        var result = await run.Do(() => executor.RunAsync(TestContext.Current.CancellationToken));
        var log = devices.Log.ToList();

        Assert.True(result.Outcome == RunOutcome.Aborted, $"{result.Outcome}: {result.FaultMessage}");
        Assert.Equal(RunState.Aborted, executor.State);
        Assert.False(run.Machine.Gate.IsFiring);
        Assert.False(run.Machine.Stage.X.IsMoving || run.Machine.Stage.Y.IsMoving);
        var firstStop = log.FindIndex(e => e.EndsWith(" stop", StringComparison.Ordinal));
        Assert.True(firstStop > 0, string.Join(", ", log));
        Assert.Equal("laser off", log[firstStop - 1]);
        Assert.DoesNotContain(log.Skip(firstStop), e => e.StartsWith("laser 1000", StringComparison.Ordinal));
        var stop = Assert.IsType<RunStopPoint>(result.StopPoint);
        Assert.NotNull(stop.XMicrosteps);
        Assert.True(result.RunsDone < job.Statistics.BurnRuns);
    }

    [Fact(Timeout = 60_000)]
    public async Task Abort_WhilePaused_EndsAbortedWithoutAnotherMove()
    {
        await using var run = SimulatedRun.Create();
        var job = TestJobs.FromMask(TestJobs.RandomMask(seed: 4, 16, 8), 1.2, new PlanOptions());
        var executor = run.Executor(job);
        var moves = 0;
        var movesWhenPaused = -1;
        executor.MoveCompleted += (_, _) =>
        {
            if (++moves == 15)
            {
                executor.Pause();
            }
        };
        executor.StateChanged += (_, e) =>
        {
            if (e.State == RunState.Paused)
            {
                movesWhenPaused = moves;
                _ = Task.Delay(TimeSpan.FromSeconds(2), run.Time).ContinueWith(_ => executor.Abort(), run.Loop);
            }
        };

        var result = await run.Do(() => executor.RunAsync(TestContext.Current.CancellationToken));

        Assert.Equal(RunOutcome.Aborted, result.Outcome);
        Assert.Equal(RunState.Aborted, executor.State);
        Assert.Equal(movesWhenPaused, moves);
        Assert.False(run.Machine.Gate.IsFiring);
        Assert.Equal(movesWhenPaused, Assert.IsType<RunStopPoint>(result.StopPoint).MoveIndex);
    }

    [Fact(Timeout = 60_000)]
    public async Task Abort_BeforePreflightEnds_EndsAbortedWithTheLaserOff()
    {
        await using var run = SimulatedRun.Create();
        var job = TestJobs.FromMask(TestJobs.RandomMask(seed: 5, 8, 4), 1, new PlanOptions());
        var executor = run.Executor(job);
        executor.StateChanged += (_, e) =>
        {
            if (e.State == RunState.Preflight)
            {
                executor.Abort();
            }
        };

        var result = await run.Do(() => executor.RunAsync(TestContext.Current.CancellationToken));

        Assert.Equal(RunOutcome.Aborted, result.Outcome);
        Assert.Equal(RunState.Aborted, executor.State);
        Assert.Equal(0, result.RunsDone);
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_Cancelled_AbortsSafely()
    {
        await using var run = SimulatedRun.Create();
        var job = TestJobs.FromMask(TestJobs.RandomMask(seed: 5, 16, 8), 1.2, new PlanOptions());
        var executor = run.Executor(job);
        using var cancel = CancellationTokenSource.CreateLinkedTokenSource(TestContext.Current.CancellationToken);
        var moves = 0;
        executor.MoveCompleted += (_, _) =>
        {
            if (++moves == 10)
            {
                cancel.Cancel();
            }
        };

        var result = await run.Do(() => executor.RunAsync(cancel.Token));

        Assert.Equal(RunOutcome.Aborted, result.Outcome);
        Assert.Equal("aborted by the operator", result.FaultMessage);
        Assert.Equal(RunState.Aborted, executor.State);
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 60_000)]
    public async Task ProgressChanged_WholeRun_IsMonotoneAndEndsAtTheTotals()
    {
        await using var run = SimulatedRun.Create();
        var job = TestJobs.FromMask(TestJobs.RandomMask(seed: 9, 20, 10), 1.5, new PlanOptions());
        var executor = run.Executor(job);
        var progress = new List<RunProgress>();
        var completedMoves = new List<Move>();
        executor.ProgressChanged += (_, p) => progress.Add(p);
        executor.MoveCompleted += (_, e) => completedMoves.Add(e.Move);

        var result = await run.Do(() => executor.RunAsync(TestContext.Current.CancellationToken));

        Assert.Equal(job.Plan.Moves(), completedMoves);
        for (var i = 1; i < progress.Count; i++)
        {
            Assert.True(progress[i].RowsDone >= progress[i - 1].RowsDone, $"rows went back at {i}");
            Assert.True(progress[i].RunsDone >= progress[i - 1].RunsDone, $"runs went back at {i}");
            Assert.True(progress[i].Percent >= progress[i - 1].Percent, $"percent went back at {i}");
            Assert.True(progress[i].Elapsed >= progress[i - 1].Elapsed, $"elapsed went back at {i}");
        }

        var last = progress[^1];
        Assert.Equal(RunState.Completed, last.State);
        Assert.Equal((job.Statistics.Rows, job.Statistics.BurnRuns), (last.RowsDone, last.RunsDone));
        Assert.Equal(100, last.Percent, 6);
        Assert.Equal(TimeSpan.Zero, last.Remaining);
        Assert.False(last.LaserOn);
        Assert.Equal((job.Plan.Moves().Last().X1, job.Plan.Moves().Last().Y1), (last.XMicrosteps, last.YMicrosteps));
        var middle = progress[progress.Count / 2];
        Assert.True(Math.Abs((middle.Elapsed + middle.Remaining).TotalSeconds - result.Duration.TotalSeconds) <= result.Duration.TotalSeconds * 0.1, $"{middle.Elapsed} + {middle.Remaining} vs {result.Duration}: engraving {result.EngravingDuration} estimated {result.EstimatedSeconds}, {middle.Percent}%");
        Assert.True(result.LaserOnSeconds > 0);
        Assert.InRange(result.LaserOnSeconds, run.Analyze(job).LaserOnSeconds * 0.95, run.Analyze(job).LaserOnSeconds * 1.05);
        Assert.Equal("PICGATE SIM-1.0", result.Machine!.Gate);
        Assert.Equal(523, result.Machine.X.FirmwareVersion);
    }
}
