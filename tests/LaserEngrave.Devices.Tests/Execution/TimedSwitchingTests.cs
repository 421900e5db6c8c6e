using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>Timed switching on the twin: the laser switched by time lands every edge where the pixel says, and nowhere else.</summary>
public class TimedSwitchingTests
{
    [Theory(Timeout = 120_000)]
    [InlineData("qr-code.bmp", 1)]
    [InlineData("qr-code.bmp", 7)]
    [InlineData("text-banner.png", 1)]
    public async Task RunAsync_Sample_EdgesWithinMicrometresNoDwellNothingOnWhiteAndAsEstimated(string sample, int seed)
    {
        await using var run = SimulatedRun.Create(new SimulatorOptions { Seed = seed });
        var job = TestJobs.FromAsset(sample, 5, new PlanOptions());

        var result = await run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken));
        var report = run.Machine.Recorder.Analyze(SimulatedRun.Grid(job), job.Mask, job.Spec.Process.BurnSpeedMmPerS);

        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        Assert.True(report.Burned.ContentEquals(job.Mask), $"{report.ExtraPixels} extra, {report.MissingPixels} missing");
        Assert.Equal(0, report.LaserOnTravelCount);
        Assert.Equal(0, report.Dwells!.Count);
        // The burst fires the pulses due before the planned switch-off, never the one more that the timed switch-off's own
        // jitter let through half the time: exit edges lie a little further in (mean 0.96 µm before the burst, about 1.04 now).
        Assert.InRange(report.Edges!.MeanErrorUm, 0, 1.1);
        Assert.InRange(report.Edges.MaxErrorUm, 0, 3);
        Assert.InRange(result.EngravingDuration.TotalSeconds, result.EstimatedEngravingSeconds * 0.99, result.EstimatedEngravingSeconds * 1.01);

        // The simulator powers up at the far end of its travel, unhomed: the whole run is as the plan and the run estimate it.
        var whole = job.Statistics.WholeRunSeconds();
        Assert.Equal(whole, result.EstimatedSeconds, 6);
        Assert.InRange(result.Duration.TotalSeconds, whole * 0.98, whole * 1.02);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_JitterDoubledAndProfileSaysSo_EdgesWithinSixMicrometresNothingOnWhite()
    {
        var options = new SimulatorOptions { AdapterLatency = new(1.0, 1.0), GateProcessing = new(0.5, 0.4) };
        await using var run = SimulatedRun.Create(options);
        var profile = MachineProfile.Default with { Latency = new LatencyProfile { StageJitterMs = 1.0, GateJitterMs = 1.0, GateProcessingJitterMs = 0.4 } };
        var job = TestJobs.FromMask(TestJobs.RandomMask(seed: 5, 24, 12, black: 0.5), 1, new PlanOptions(), profile: profile);

        var result = await run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken));
        var report = run.Machine.Recorder.Analyze(SimulatedRun.Grid(job), job.Mask, job.Spec.Process.BurnSpeedMmPerS);

        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        Assert.True(report.Burned.ContentEquals(job.Mask), $"{report.ExtraPixels} extra, {report.MissingPixels} missing");
        Assert.InRange(report.Edges!.MaxErrorUm, 0, 6);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_StageReplyLate_EndsFailedWithTheLaserOffAndNothingOnWhite()
    {
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = "delay:stage:after=31:ms=300" });
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions());

        var result = await run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken));
        var report = run.Machine.Recorder.Analyze(SimulatedRun.Grid(job), job.Mask, job.Spec.Process.BurnSpeedMmPerS);

        Assert.Equal(RunOutcome.Failed, result.Outcome);
        Assert.Contains("the laser was to come on", result.FaultMessage, StringComparison.Ordinal);
        Assert.True(result.LaserOffConfirmed);
        Assert.False(run.Machine.Gate.IsFiring);
        Assert.Equal(0, report.ExtraPixels);
        Assert.Equal(0, report.Dwells!.Pulses);
    }

    [Fact(Timeout = 60_000)]
    public async Task RunAsync_PixelTooShortForTheGate_RefusedBeforeAnythingMovesNamingTheSpeed()
    {
        await using var run = SimulatedRun.Create();
        var process = ProcessSettings.Default with { BurnSpeedMmPerS = 4 };
        var job = TestJobs.FromMask(TestJobs.Mask("#.#.#.#.", ".#.#.#.#"), 0.08, new PlanOptions(), process: process);

        var ex = await Assert.ThrowsAsync<PreflightException>(() => run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken)));

        Assert.StartsWith("at a pitch of 10 µm a pixel lasts 2.5 ms at the burn speed", ex.Message, StringComparison.Ordinal);
        Assert.Contains("burn at ", ex.Message, StringComparison.Ordinal);
        Assert.False(run.Machine.Stage.X.IsMoving);
    }
}
