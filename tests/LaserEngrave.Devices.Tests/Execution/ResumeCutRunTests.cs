using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>A run cut off in the middle of a burn run resumes from the first pixel not completely burned.</summary>
public sealed class ResumeCutRunTests
{
    [Theory(Timeout = 120_000)]
    [InlineData(0.4)]
    [InlineData(1.3)]
    [InlineData(2.9)]
    public async Task AbortMidRun_ThenResume_OnlyThePixelCutThroughBurnsTwice(double secondsIntoTheRun)
    {
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create();
        var job = TestJobs.FromMask(TestJobs.Mask("################", "....############"), 4, new PlanOptions());

        var stop = await AbortPartWayAsync(run, job, secondsIntoTheRun, ct);
        var resumeX = Assert.IsType<long>(stop.ResumeXMicrosteps);
        var cut = Assert.IsType<PixelIndex>(stop.CutPixel);
        Assert.Null(stop.ExpectedXMicrosteps);

        await run.RecoverAsync();
        var resumed = await run.Do(() => run.Executor(job, new RunOptions { ResumeFrom = stop }).RunAsync(ct));
        var report = run.Analyze(job);

        Assert.Equal(RunOutcome.Completed, resumed.Outcome);
        Assert.True(report.Burned.ContentEquals(job.Mask), $"{report.ExtraPixels} extra, {report.MissingPixels} missing");
        Assert.Equal(0, report.LaserOnTravelCount);
        var twice = BurnedTwice(job, report);
        Assert.True(twice.Count <= 1, string.Join(", ", twice));
        Assert.All(twice, p => Assert.Equal(cut, p));
        Assert.Equal(job.Geometry.Geometry.RunEdgeX(cut.Column + (cut.Row % 2 == 0 ? 0 : 1), cut.Row), resumeX);
    }

    [Theory(Timeout = 120_000)]
    [InlineData(false)]
    [InlineData(true)]
    public async Task AbortMidRun_XAxisSilent_ResumesMidRunOnlyWhereItsMotionWasTakingIt(bool movedSince)
    {
        // The 33rd stage command is the first stroke's Move Absolute: from then on X answers nothing (its port lost),
        // so the stop after the abort cannot be confirmed and the stop point says where X must be found.
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = "silent:stage:after=33" });
        var job = TestJobs.FromMask(TestJobs.Mask("################", "....############"), 4, new PlanOptions());
        var stop = await AbortPartWayAsync(run, job, 1.3, ct);
        var expected = Assert.IsType<long>(stop.ExpectedXMicrosteps);
        Assert.NotNull(stop.ResumeXMicrosteps);

        await run.RecoverAsync();
        if (movedSince)
        {
            // Someone jogged X after the fault: the time the laser went off no longer says where it burned.
            await run.Do(async () => await run.Stage.X.MoveAbsoluteAsync(expected - 5000, ct));
        }

        var resumed = await run.Do(() => run.Executor(job, new RunOptions { ResumeFrom = stop }).RunAsync(ct));
        var report = run.Analyze(job);

        Assert.Equal(RunOutcome.Completed, resumed.Outcome);
        Assert.True(report.Burned.ContentEquals(job.Mask));
        var twice = BurnedTwice(job, report);
        var cut = stop.CutPixel!.Value;
        if (movedSince)
        {
            // Burned again from the run's start: every pixel it had burned whole (and the one cut through, part of it).
            Assert.InRange(twice.Count, cut.Column, cut.Column + 1);
            Assert.True(twice.Count > 1);
        }
        else
        {
            // At most the pixel cut through (it gets its part burned before the fault on top of a whole burn).
            Assert.True(twice.Count <= 1, string.Join(", ", twice));
            Assert.All(twice, p => Assert.Equal(cut, p));
        }
    }

    [Theory(Timeout = 120_000)]
    [InlineData(6)]
    [InlineData(9)]
    public async Task GateLinkLostMidRun_ResumesWhereTheGatesWatchdogSwitchedTheLaserOff(int gateCommand)
    {
        // Preflight sends the gate 3 lines; then the switch-on and a keepalive every 250 ms: the link goes part-way into the run.
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = $"disconnect:gate:after={gateCommand}" });
        var job = TestJobs.FromMask(TestJobs.Mask("################", "....############"), 4, new PlanOptions());

        var failed = await run.Do(() => run.Executor(job).RunAsync(ct));
        await run.Do(() => Task.Delay(TimeSpan.FromMilliseconds(run.Machine.Profile.Gate.WatchdogMs * 2), run.Time, ct));
        var stop = Assert.IsType<RunStopPoint>(failed.StopPoint);
        Assert.Equal(RunOutcome.Failed, failed.Outcome);
        Assert.False(failed.LaserOffConfirmed);
        Assert.True(stop.OffByGateWatchdog);
        Assert.NotNull(stop.ResumeXMicrosteps);

        await run.RecoverAsync();
        var resumed = await run.Do(() => run.Executor(job, new RunOptions { ResumeFrom = stop }).RunAsync(ct));
        var report = run.Analyze(job);

        Assert.Equal(RunOutcome.Completed, resumed.Outcome);
        Assert.True(report.Burned.ContentEquals(job.Mask));
        var twice = BurnedTwice(job, report);
        Assert.True(twice.Count <= 1, string.Join(", ", twice));
        Assert.All(twice, p => Assert.Equal(stop.CutPixel, p));
    }

    [Fact(Timeout = 120_000)]
    public async Task StopPointCountingOnTheWatchdog_GateDoesNotReportItTripped_BurnedAgainFromTheRunsStart()
    {
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create();
        var job = TestJobs.FromMask(TestJobs.Mask("################", "....############"), 4, new PlanOptions());
        var stop = await AbortPartWayAsync(run, job, 1.3, ct);

        // As if the gate had lost its link: a gate whose watchdog never tripped cannot vouch for when the laser went off.
        var resumed = await run.Do(() => run.Executor(job, new RunOptions { ResumeFrom = stop with { OffByGateWatchdog = true } }).RunAsync(ct));
        var report = run.Analyze(job);

        Assert.Equal(RunOutcome.Completed, resumed.Outcome);
        Assert.True(report.Burned.ContentEquals(job.Mask));
        Assert.InRange(BurnedTwice(job, report).Count, stop.CutPixel!.Value.Column, stop.CutPixel.Value.Column + 1);
    }

    private static async Task<RunStopPoint> AbortPartWayAsync(SimulatedRun run, PreparedJob job, double seconds, CancellationToken ct)
    {
        var executor = run.Executor(job);
        var aborting = 0;
        executor.ProgressChanged += (_, p) =>
        {
            if (p.LaserOn && p.State == RunState.Running && Interlocked.Exchange(ref aborting, 1) == 0)
            {
                _ = Task.Delay(TimeSpan.FromSeconds(seconds), run.Time).ContinueWith(_ => executor.Abort(), run.Loop);
            }
        };

        var aborted = await run.Do(() => executor.RunAsync(ct));
        Assert.Equal(RunOutcome.Aborted, aborted.Outcome);
        return Assert.IsType<RunStopPoint>(aborted.StopPoint);
    }

    // A pixel burned twice gets twice its pulses (250 µm at 1 µm apart: 250): count those above one and a half.
    private static List<PixelIndex> BurnedTwice(PreparedJob job, LaserEngrave.Simulator.Burn.BurnReport report)
    {
        var nominal = job.Geometry.PitchUm / (job.Spec.Process.BurnSpeedMmPerS * 1000 / job.Spec.Process.LaserFrequencyWholeHz);
        var twice = new List<PixelIndex>();
        for (var row = 0; row < job.Mask.Height; row++)
        {
            for (var column = 0; column < job.Mask.Width; column++)
            {
                if (report.Dose.PulsesOnPixel(column, row) > 1.5 * nominal)
                {
                    twice.Add(new PixelIndex(column, row));
                }
            }
        }

        return twice;
    }
}
