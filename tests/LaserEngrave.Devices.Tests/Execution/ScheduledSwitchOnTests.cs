using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Timing;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>
/// Switch-ons the gate times (issue 34): a gate whose CAPS? lists AFTER gets each burn run's switch-on as a scheduled
/// burst written ahead of time, so a host late by less than the slack moves no edge.
/// </summary>
public class ScheduledSwitchOnTests
{
    // A computer late to wake from its waits (the realistic twin's 0.5 ms, 1 % up to 5 ms), which scheduled switch-ons
    // absorb: one executor, no recovery. Its stalls between a stamp and the write are another matter (the delay in the
    // line was computed at the stamp), a timing doubt the session goes on from: LoadedComputerRunTests.
    private static readonly HostLateness WakesLate = HostLateness.Realistic with { StallProbability = 0, LateReadProbability = 0 };

    private static PreparedJob QrAt(double speedMmPerS) =>
        TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions(), ProcessSettings.Default with { BurnSpeedMmPerS = speedMmPerS });

    [Theory(Timeout = 300_000)]
    [InlineData(1)]
    [InlineData(3)]
    public async Task RunAsync_QrAt4MmPerSOnALateHost_CompletesWithNoPulseOnWhite(int seed)
    {
        // Before: 0.375 ms of lateness was past the 1.5 µm edge tolerance at 4 mm/s, and the run stopped at its first doubt.
        var job = QrAt(4);
        await using var run = SimulatedRun.Create(new SimulatorOptions { HostLateness = WakesLate, Seed = seed });

        var result = await run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken));
        var report = run.Machine.Recorder.Analyze(SimulatedRun.Grid(job), job.Mask, 4);

        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        Assert.Equal((0, 0L, 0L), (report.LaserOnTravelCount, report.ExtraPixels, report.MissingPixels));
        Assert.Contains(run.Written, w => w.Port == "gate" && w.Line.StartsWith("BURST ", StringComparison.Ordinal) && w.Line.Contains(" AFTER ", StringComparison.Ordinal));
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 300_000)]
    public async Task RunAsync_ScheduledGate_NoSwitchOffWrittenBetweenAScheduledLineAndItsFirstPulse()
    {
        // A later OFF cancels an armed burst: every scheduled line is followed by the next burst's line or by its own run's end.
        var job = QrAt(4);
        await using var run = SimulatedRun.Create(new SimulatorOptions { HostLateness = WakesLate, Seed = 2 });

        var result = await run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken));
        var gate = run.Written.Where(w => w.Port == "gate").ToList();
        var report = run.Machine.Recorder.Analyze(SimulatedRun.Grid(job), job.Mask, 4);

        Assert.Equal(RunOutcome.Completed, result.Outcome);
        Assert.True(report.Burned.ContentEquals(job.Mask));
        for (var i = 0; i + 1 < gate.Count; i++)
        {
            if (gate[i].Line.Contains(" AFTER ", StringComparison.Ordinal) && gate[i + 1].Line == "OFF")
            {
                var afterUs = int.Parse(gate[i].Line.Split(' ')[^1], System.Globalization.CultureInfo.InvariantCulture);
                Assert.True(gate[i + 1].Seconds > gate[i].Seconds + (afterUs / 1e6), $"OFF at {gate[i + 1].Seconds:0.0000} s before the burst of '{gate[i].Line}' at {gate[i].Seconds:0.0000} s began");
            }
        }
    }

    [Fact(Timeout = 300_000)]
    public async Task RunAsync_FrequencyOnlyGate_SendsNoScheduledBurstAndNoCapabilitiesQuestion()
    {
        var profile = FrequencyOnlyGateTests.Profile() with { EdgeToleranceUm = MachineProfile.Default.EdgeToleranceUm };
        var job = FrequencyOnlyGateTests.Job("qr-code.bmp", profile);
        await using var run = SimulatedRun.Create(profile: profile);

        var result = await run.Do(() => run.Executor(job, new RunOptions { AcceptNoWatchdog = true }).RunAsync(TestContext.Current.CancellationToken));

        Assert.Equal(RunOutcome.Completed, result.Outcome);
        Assert.DoesNotContain(run.Written, w => w.Port == "gate" && (w.Line.Contains("AFTER", StringComparison.Ordinal) || w.Line.StartsWith("CAPS", StringComparison.Ordinal)));
    }

    [Fact(Timeout = 300_000)]
    public async Task RunAsync_QrAt4MmPerSOnAGateWithoutAfter_RefusedAtPreflightNamingTheFastestBeforeTheStageHearsAnything()
    {
        // Issue 34: what this computer can hold is said once the gate has answered CAPS?, before either axis is asked or moved.
        var job = QrAt(4);
        await using var run = SimulatedRun.Create(new SimulatorOptions { GateScheduledBursts = false });

        var refused = await Assert.ThrowsAsync<PreflightException>(() => run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken)));

        Assert.Equal(SpeedHold.Problem(4, MachineProfile.Default, scheduled: false), refused.Message);
        Assert.Contains("the fastest it holds is 3 mm/s", refused.Message, StringComparison.Ordinal);
        Assert.DoesNotContain(run.Written, w => w.Port == "stage");
        Assert.DoesNotContain(run.Written, w => w.Port == "gate" && w.Line.StartsWith("BURST ", StringComparison.Ordinal));
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 300_000)]
    public async Task RunAsync_GateWithoutAfter_SendsPlainBurstsAndCompletes()
    {
        // An older gate refuses CAPS?: it is never sent a scheduled burst, which it would refuse (or, a loose one, fire at once).
        var job = QrAt(1);
        await using var run = SimulatedRun.Create(new SimulatorOptions { GateScheduledBursts = false });

        var result = await run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken));
        var report = run.Machine.Recorder.Analyze(SimulatedRun.Grid(job), job.Mask, 1);

        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        Assert.True(report.Burned.ContentEquals(job.Mask));
        Assert.Contains(run.Written, w => w.Port == "gate" && w.Line == "CAPS?");
        Assert.DoesNotContain(run.Written, w => w.Port == "gate" && w.Line.Contains("AFTER", StringComparison.Ordinal));
        Assert.Equal(job.Statistics.BurnRuns, run.Written.Count(w => w.Port == "gate" && w.Line.StartsWith("BURST ", StringComparison.Ordinal)));
    }

    [Fact(Timeout = 300_000)]
    public async Task RunAsync_QrAt1MmPerSOnALateHost_CompletesInOneRunAndTheEstimateHolds()
    {
        // Before: a switch-on later than the tolerance cost a recovery, about 1 in 100 runs, and the run 5 % of its estimate.
        var job = QrAt(1);
        await using var run = SimulatedRun.Create(new SimulatorOptions { HostLateness = WakesLate, Seed = 4 });

        var result = await run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken));
        var report = run.Machine.Recorder.Analyze(SimulatedRun.Grid(job), job.Mask, 1);

        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        Assert.Equal((0, 0L, 0L), (report.LaserOnTravelCount, report.ExtraPixels, report.MissingPixels));
        // A switch-on that must wait for a position query and whose host stalls past the planned slack still goes plainly: rare.
        Assert.InRange(result.LateSwitches?.Count ?? 0, 0, 2);
        Assert.InRange(report.Edges!.MaxErrorUm, 0, 3);
        Assert.InRange(result.EngravingDuration.TotalSeconds / job.Statistics.EngravingSeconds, 0.995, 1.005);
    }

    [Fact(Timeout = 300_000)]
    public async Task RunAsync_PositionReplyAfterAFlownGapLateButBeforeTheSwitchOn_IsATimingDoubtNotAPosition()
    {
        // Issue 34: a reply that came back well past its round trip says nothing of when the axis answered; before, its
        // position was taken at face value (on a loaded PC: "ahead of plan", and the switch-on moved into the white).
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions());
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = "delay:stage:after=34:ms=8" });

        var result = await run.Do(() => run.Executor(job).RunAsync(TestContext.Current.CancellationToken));
        var report = run.Machine.Recorder.Analyze(SimulatedRun.Grid(job), job.Mask, job.Spec.Process.BurnSpeedMmPerS);

        Assert.Equal(RunOutcome.Failed, result.Outcome);
        Assert.Contains("too late to locate the stage, so the laser stays off", result.FaultMessage, StringComparison.Ordinal);
        Assert.True(result.Recoverable);
        Assert.True(result.LaserOffConfirmed);
        Assert.Equal((0, 0L), (report.LaserOnTravelCount, report.ExtraPixels));
    }
}
