using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Devices.LaserGate;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Devices.Zaber;
using LaserEngrave.Simulator;
using LaserEngrave.Testing;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>A whole run through the real serial path: ZaberChain and PicLaserGate on socat ptys, the simulator on the other ends.</summary>
public class PtyRunTests
{
    [Fact(Timeout = 120_000)]
    public async Task RunAsync_ThroughSocatPtys_BurnsExactlyTheMask()
    {
        var ct = TestContext.Current.CancellationToken;
        // On ports the simulator runs on the wall clock, where this machine's load (the tests run in parallel) can shift
        // it by more than any latency model: the serial path is tested here step by step (paper), timed switching in
        // virtual time (RunExecutorTests, ExecutionFigures).
        var profile = MachineProfile.Default;
        await using var stagePair = await SocatPtyPair.StartAsync(ct);
        await using var laserPair = await SocatPtyPair.StartAsync(ct);
        // On ports the simulator runs on the wall clock: it starts 1 mm from home so that homing takes a moment.
        await using var machine = SimulatedMachine.Attach(SerialPortLink.Open(stagePair.A), SerialPortLink.Open(laserPair.A), profile, new SimulatorOptions { StartMm = 1 });
        await using var stage = ZaberChain.Open(stagePair.B, profile);
        await using var gate = PicLaserGate.Open(laserPair.B, profile.Gate);
        // 1 mm from home too, so that the travel to the job takes a moment (the run is on the wall clock).
        var job = TestJobs.FromMask(TestJobs.Mask("#..##.", ".####.", "#....#"), 0.6, new PlanOptions { Strategy = PlanStrategy.Paper }, new OriginMm(1, 1), profile: profile);

        var result = await new RunExecutor(stage, gate, job).RunAsync(ct);
        var report = machine.Recorder.Analyze(SimulatedRun.Grid(job), job.Mask);

        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        Assert.True(report.Burned.ContentEquals(job.Mask), $"burned differs: {report.ExtraPixels} extra, {report.MissingPixels} missing");
        Assert.Equal(0, report.LaserOnTravelCount);
        Assert.False(machine.Gate.IsFiring);
    }
}
