using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>A switch-off the gate refuses or leaves unanswered never ends in "confirmed" without saying which path confirmed it.</summary>
public sealed class RefusedSwitchOffTests
{
    // The 32nd gate line of the QR job at 5 mm is a stroke's timed OFF (issue 19, item 1; one line on since CAPS?).
    private const string RefusedOff = "error:gate:after=31";

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_GateRefusesTheSwitchOff_EveryPathGoesOutAndOffAgainConfirmsIt()
    {
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = RefusedOff });
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions());
        var refusedAt = double.NaN;
        run.Machine.Faults.Triggered += (_, _) => refusedAt = run.Machine.NowSeconds;

        var failed = await run.Do(() => run.Executor(job).RunAsync(ct));
        var lastOn = run.Machine.Recorder.LaserOnIntervals(run.Machine.NowSeconds)[^1];

        Assert.Equal(RunOutcome.Failed, failed.Outcome);
        Assert.Contains("refused 'OFF'", failed.FaultMessage, StringComparison.Ordinal);
        Assert.True(failed.LaserOffConfirmed);
        Assert.Equal(LaserOffPath.OffAgain, failed.LaserOffBy);
        Assert.False(run.Machine.Gate.IsFiring);

        // Off one round trip after the refusal: its reply (16 bytes) and the new OFF (4 bytes) on the 9600 baud line; or
        // a moment before it, when the burst counted itself out while the refused OFF was being processed.
        Assert.InRange(lastOn.To - refusedAt, -0.001, 0.030);
        Assert.Equal(50, run.Machine.Gate.WatchdogMs);
        var summary = RunSummaryText.LaserOff(new RunFault(failed.FaultMessage!, null, failed.LaserOffConfirmed, failed.LaserOffBy));
        Assert.Contains("OFF, late or sent again", summary, StringComparison.Ordinal);
        Assert.DoesNotContain("confirmed by the gate (it acknowledged OFF)", summary, StringComparison.Ordinal);
    }

    [Theory(Timeout = 120_000)]
    [InlineData("error:gate:after=30:count=all")]
    [InlineData("no-ack:gate:after=30")]
    public async Task RunAsync_GateAcknowledgesNoPathToOff_NotConfirmedPortClosedAndItsWatchdogSwitchesTheLaserOff(string fault)
    {
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = fault });
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions());

        var failed = await run.Do(() => run.Executor(job).RunAsync(ct));
        Assert.False(run.Gate.IsOpen);
        await run.Do(() => Task.Delay(TimeSpan.FromMilliseconds(run.Machine.Profile.Gate.WatchdogMs * 1.5), run.Time, ct));

        Assert.Equal(RunOutcome.Failed, failed.Outcome);
        Assert.False(failed.LaserOffConfirmed);
        Assert.Equal(LaserOffPath.None, failed.LaserOffBy);
        Assert.Contains("a person must check the laser", failed.FaultMessage, StringComparison.Ordinal);
        Assert.False(run.Machine.Gate.IsFiring, "the gate's watchdog did not switch the laser off once its port was closed");
        Assert.Contains("NOT CONFIRMED", RunSummaryText.LaserOff(new RunFault(failed.FaultMessage!, null, false, failed.LaserOffBy)), StringComparison.Ordinal);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_StageFault_TheUsualOffConfirmsIt()
    {
        var ct = TestContext.Current.CancellationToken;
        await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = "error:stage:after=60" });
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions());

        var failed = await run.Do(() => run.Executor(job).RunAsync(ct));

        Assert.Equal(RunOutcome.Failed, failed.Outcome);
        Assert.Equal(LaserOffPath.Off, failed.LaserOffBy);
        Assert.Equal(run.Machine.Profile.Gate.WatchdogMs, run.Machine.Gate.WatchdogMs);
    }
}
