using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>Every fault the simulator injects, in the middle of a run: the run fails safely, and a resumed run finishes the image exactly.</summary>
public class RunFaultTests
{
    // Preflight takes about 20 stage commands and 3 gate lines; these land in the middle of the plan.
    [Theory(Timeout = 120_000)]
    [InlineData("drop-reply:stage:after=60")]
    [InlineData("corrupt:stage:after=60")]
    [InlineData("delay:stage:after=60:ms=5000")]
    [InlineData("error:stage:after=60")]
    [InlineData("silent:stage:after=60")]
    [InlineData("disconnect:stage:after=60")]
    [InlineData("drop-reply:gate:after=12")]
    [InlineData("corrupt:gate:after=12:byte=0")]
    [InlineData("delay:gate:after=12:ms=2000")]
    [InlineData("error:gate:after=12")]
    [InlineData("silent:gate:after=12")]
    [InlineData("disconnect:gate:after=12")]
    [InlineData("no-ack:gate:after=12")]
    public async Task RunAsync_FaultMidRun_FailsWithLaserOffAndResumeFinishesTheMask(string fault)
    {
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = fault });
        var job = TestJobs.FromMask(TestJobs.RandomMask(seed: 11, 16, 10), 1.2, new PlanOptions { OverscanMm = 0.05 });

        var failed = await run.Do(() => run.Executor(job).RunAsync(ct));
        if (!failed.LaserOffConfirmed)
        {
            // The gate could not be told: its own watchdog is what switches the laser off.
            await run.Do(() => Task.Delay(TimeSpan.FromMilliseconds(run.Machine.Profile.Gate.WatchdogMs * 2), run.Time, ct));
        }

        Assert.Equal(RunOutcome.Failed, failed.Outcome);
        Assert.False(run.Machine.Gate.IsFiring, "the laser is still on after the fault");
        Assert.NotNull(failed.FaultMessage);
        Assert.DoesNotContain('\n', failed.FaultMessage);
        var stop = Assert.IsType<RunStopPoint>(failed.StopPoint);
        Assert.InRange(stop.MoveIndex, 0, job.Statistics.Moves);
        Assert.True(failed.RunsDone < job.Statistics.BurnRuns, "the fault struck after the last run");

        await run.RecoverAsync();
        var resumed = await run.Do(() => run.Executor(job, new RunOptions { ResumeFrom = stop }).RunAsync(ct));
        var report = run.Analyze(job);

        Assert.Equal(RunOutcome.Completed, resumed.Outcome);
        Assert.Equal(job.Statistics.BurnRuns, resumed.RunsDone);
        Assert.True(report.Burned.ContentEquals(job.Mask), $"{fault}: burned differs after resuming: {report.ExtraPixels} extra, {report.MissingPixels} missing");
        Assert.Equal(0, report.LaserOnTravelCount);
        Assert.False(run.Machine.Gate.IsFiring);
    }

    // The 10th and 16th position queries of the QR job at 5 mm: one before a stroke's first switch-on, one after a flown gap.
    [Theory(Timeout = 120_000)]
    [InlineData(9)]
    [InlineData(15)]
    public async Task RunAsync_PositionQueryAnsweredPastItsDeadline_TheLaserStaysOffAndNothingBurnsOffItsPixels(int after)
    {
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = $"delay:stage:device=1:command=60:after={after}:ms=150" });
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions());

        var failed = await run.Do(() => run.Executor(job).RunAsync(ct));
        var report = run.Machine.Recorder.Analyze(SimulatedRun.Grid(job), job.Mask, job.Spec.Process.BurnSpeedMmPerS);

        // The deadline is the switch-on's: past it the laser must stay off, not come on late past its edge (as it did
        // when the wait's end left the simulation's loop and the clock ran on to the late answer).
        Assert.Equal(RunOutcome.Failed, failed.Outcome);
        Assert.Contains("did not answer the position query", failed.FaultMessage, StringComparison.Ordinal);
        Assert.Equal((0L, 0), (report.ExtraPixels, report.LaserOnTravelCount));
        Assert.True(report.Edges is { MaxErrorUm: <= 3 }, $"edges {report.Edges}");
        Assert.False(run.Machine.Gate.IsFiring);
    }
}
