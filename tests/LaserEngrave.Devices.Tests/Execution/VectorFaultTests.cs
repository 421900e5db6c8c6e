using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>A drawing's run that fails or is aborted leaves the laser off with nothing off the path, and resumes from its stroke.</summary>
public class VectorFaultTests
{
    private static PreparedDrawing Hexagons() => PreparedDrawing.Prepare(
        new JobSpec { ImagePath = TestJobs.AssetPath(Path.Combine("drawings", "hexagons.dxf")), Size = SizeSpec.Width(4), Origin = new OriginMm(5, 5) },
        VectorOptions.Default);

    // Preflight, the setup and the first travel take about 30 stage commands and 3 gate lines; these land among the strokes.
    // A stage fault must never leave the laser on off the path; a lost reply to a speed change the axis carried out
    // (its later replies show it) may let the run complete.
    [Theory(Timeout = 120_000)]
    [InlineData("drop-reply:stage:after=150", true)]
    [InlineData("corrupt:stage:after=150", true)]
    [InlineData("delay:stage:after=150:ms=5000", false)]
    [InlineData("error:stage:after=150", false)]
    [InlineData("silent:stage:after=150", false)]
    [InlineData("disconnect:stage:after=150", false)]
    public async Task RunAsync_StageFaultMidDrawing_LaserOffNothingOffThePathAndResumeFinishes(string fault, bool mayComplete)
    {
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = fault });
        var job = Hexagons();

        var first = await run.Do(() => new RunExecutor(run.Stage, run.Gate, job, run.Time).RunAsync(ct));
        var during = run.Machine.Recorder.AnalyzePaths(job.Plan.Paths, job.Spec.Process.BurnSpeedMmPerS);
        // Until a stage that stopped acting is noticed (its reply a stall margin late, about 30 ms), the spot goes
        // straight on: on a small circle a few micrometres, never further than the off-path limit.
        Assert.False(run.Machine.Gate.IsFiring, "the laser is still on after the fault");
        Assert.Equal(0, during.OffPathPulses);
        if (first.Outcome == RunOutcome.Completed)
        {
            Assert.True(mayComplete, $"{fault} went unnoticed");
            return;
        }

        Assert.Equal(RunOutcome.Failed, first.Outcome);
        Assert.DoesNotContain('\n', first.FaultMessage!);
        await ResumeAndCheckAsync(run, job, first, ct);
    }

    // A gate that does not carry out a switch-off can only be stopped by its own watchdog: the stage stops, the run
    // fails, and the run that resumes it is clean.
    [Theory(Timeout = 120_000)]
    [InlineData("drop-reply:gate:after=12")]
    [InlineData("delay:gate:after=12:ms=2000")]
    [InlineData("error:gate:after=12")]
    [InlineData("silent:gate:after=12")]
    [InlineData("no-ack:gate:after=12")]
    public async Task RunAsync_GateFaultMidDrawing_FailsLaserOffAndResumeFinishesOnThePath(string fault)
    {
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = fault });
        var job = Hexagons();

        var failed = await run.Do(() => new RunExecutor(run.Stage, run.Gate, job, run.Time).RunAsync(ct));
        if (!failed.LaserOffConfirmed)
        {
            // The gate could not be told: its own watchdog is what switches the laser off.
            await run.Do(() => Task.Delay(TimeSpan.FromMilliseconds(run.Machine.Profile.Gate.WatchdogMs * 2), run.Time, ct));
        }

        Assert.Equal(RunOutcome.Failed, failed.Outcome);
        Assert.False(run.Machine.Gate.IsFiring, "the laser is still on after the fault");
        Assert.DoesNotContain('\n', failed.FaultMessage!);
        await ResumeAndCheckAsync(run, job, failed, ct);
    }

    private static async Task ResumeAndCheckAsync(SimulatedRun run, PreparedDrawing job, RunResult failed, CancellationToken ct)
    {
        var stop = Assert.IsType<RunStopPoint>(failed.StopPoint);
        Assert.InRange(stop.MoveIndex, 0, job.Schedule.Strokes.Count - 1);
        await run.RecoverAsync();
        run.Machine.Recorder.Restart(run.Machine.NowSeconds);

        var resumed = await run.Do(() => new RunExecutor(run.Stage, run.Gate, job, run.Time, new RunOptions { ResumeFrom = stop }).RunAsync(ct));
        var report = run.Machine.Recorder.AnalyzePaths(job.Plan.Paths, job.Spec.Process.BurnSpeedMmPerS);

        Assert.Equal(RunOutcome.Completed, resumed.Outcome);
        Assert.Equal(job.Schedule.Strokes.Count, resumed.RowsDone);
        Assert.Equal(0, report.OffPathPulses);
        Assert.Equal(0, report.DwellCount);
        Assert.InRange(report.DeviationMaxUm, 0, 3);
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 120_000)]
    public async Task Abort_MidDrawing_LaserOffStageStoppedAndResumeFromTheStrokeCompletes()
    {
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create();
        var job = Hexagons();
        var executor = new RunExecutor(run.Stage, run.Gate, job, run.Time);
        executor.ProgressChanged += (_, p) =>
        {
            if (p.RowsDone == 3)
            {
                executor.Abort();
            }
        };

        var aborted = await run.Do(() => executor.RunAsync(ct));

        Assert.Equal(RunOutcome.Aborted, aborted.Outcome);
        Assert.False(run.Machine.Gate.IsFiring);
        var stop = Assert.IsType<RunStopPoint>(aborted.StopPoint);
        Assert.Equal(3, stop.MoveIndex);

        var resumed = await run.Do(() => new RunExecutor(run.Stage, run.Gate, job, run.Time, new RunOptions { ResumeFrom = stop }).RunAsync(ct));
        var report = run.Machine.Recorder.AnalyzePaths(job.Plan.Paths, job.Spec.Process.BurnSpeedMmPerS);

        Assert.Equal(RunOutcome.Completed, resumed.Outcome);
        Assert.Equal(0, report.OffPathPulses);
        Assert.Equal(0, report.DwellCount);
        Assert.Equal(job.Schedule.Strokes.Count, resumed.RowsDone);
    }

    [Fact(Timeout = 120_000)]
    public async Task PauseResume_MidDrawing_PausesBetweenStrokesWithTheLaserOffAndFinishesOnThePath()
    {
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create();
        var job = Hexagons();
        var executor = new RunExecutor(run.Stage, run.Gate, job, run.Time);
        var laserOnWhilePaused = false;
        executor.ProgressChanged += (_, p) =>
        {
            if (p.RowsDone == 2 && p.State == RunState.Running)
            {
                executor.Pause();
            }
        };
        executor.StateChanged += (_, e) =>
        {
            if (e.State == RunState.Paused)
            {
                laserOnWhilePaused |= run.Machine.Gate.IsFiring;
                _ = run.Time.CreateTimer(_ => executor.Resume(), null, TimeSpan.FromSeconds(2), Timeout.InfiniteTimeSpan);
            }
        };

        var result = await run.Do(() => executor.RunAsync(ct));
        var report = run.Machine.Recorder.AnalyzePaths(job.Plan.Paths, job.Spec.Process.BurnSpeedMmPerS);

        Assert.Equal(RunOutcome.Completed, result.Outcome);
        Assert.False(laserOnWhilePaused);
        Assert.Equal(0, report.OffPathPulses);
        Assert.Equal(0, report.DwellCount);
        Assert.InRange(report.DeviationMaxUm, 0, 3);
    }
}
