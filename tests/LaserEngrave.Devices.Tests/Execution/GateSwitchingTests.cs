using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Execution;
using Microsoft.Extensions.Time.Testing;
using NSubstitute;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>The timed laser's lines alone (<see cref="GateSwitching"/>): bursts sized as written, late writes counted or refused, the gate's wire queue.</summary>
public class GateSwitchingTests
{
    private static readonly TimedSwitching Timing = TimedSwitching.For(ProcessSettings.Default, MachineProfile.Default, MachineProfile.Default.X.MicrostepUm);

    [Fact]
    public async Task SendSwitchOnAsync_OnTime_SendsOneBurstEndingBeforeTheOffEdge()
    {
        var (switching, gate, _) = Make(now: 1.0);
        var onEffect = 1.0 + Timing.OnLeadSeconds;
        var offEffect = onEffect + 0.01;

        await switching.SendSwitchOnAsync(onEffect, offEffect, Timing);

        var pulses = Timing.BurstPulses(1.0, double.NegativeInfinity, offEffect);
        await gate.Received(1).BurstAsync(pulses, Timing.FrequencyHz, Arg.Any<CancellationToken>());
        Assert.True(pulses >= 1);
        // Its count ends it at the off edge, give or take a pulse, the gate's processing and its jitter.
        Assert.InRange(switching.BurstEndsAt, onEffect, offEffect + (1.0 / Timing.FrequencyHz) + Timing.GateProcessingSeconds + Timing.GateJitterSeconds);
        Assert.Null(switching.Late);
    }

    [Fact]
    public async Task SendSwitchOnAsync_HostLateBeyondTheEdgeTolerance_LeavesTheLaserOffAndFaultsRecoverably()
    {
        // Written a whole second after its edge: nothing goes to the gate, the run ends as a timing doubt.
        var (switching, gate, run) = Make(now: 2.0);

        await Assert.ThrowsAsync<DeviceException>(() => switching.SendSwitchOnAsync(1.0, 1.01, Timing));

        await gate.DidNotReceiveWithAnyArgs().BurstAsync(default, default, TestContext.Current.CancellationToken);
        Assert.Equal([true], run.Faults.Select(f => f.Recoverable));
        Assert.StartsWith("this computer was ", run.Faults[0].Reason, StringComparison.Ordinal);
    }

    [Fact]
    public async Task SendSwitchOffAsync_RightAfterABurst_ExpectsItsReplyBehindTheBurst()
    {
        var (switching, _, _) = Make(now: 1.0);
        Assert.Equal(0, switching.QueueSeconds(Timing, 1.0), 12);

        await switching.SendSwitchOffAsync(Timing);

        Assert.True(switching.QueueSeconds(Timing, 1.0) > 0, "a switch-off written now waits behind the one just sent");
        Assert.True(switching.WireFree > 1.0);
    }

    [Fact]
    public void NoteSwitchOffLate_CountingGateLateBeyondTolerance_CountsItAndGoesOn()
    {
        // The burst stopped the laser at the run's end already: a late OFF is logged, not a fault.
        var (switching, _, run) = Make(now: 1.0);

        switching.NoteSwitchOffLate(1.0, 1.05, Timing);

        Assert.Equal(1, switching.Late?.LateOffs);
        Assert.Empty(run.Faults);
    }

    [Fact]
    public void NoteSwitchOffLate_FrequencyOnlyGateLateBeyondTolerance_FaultsTheRun()
    {
        var profile = MachineProfile.Default with { Gate = new LaserGateProfile { Kind = LaserGateKind.FrequencyOnly, WatchdogMs = 0 } };
        var (switching, _, run) = Make(now: 1.0, profile);

        Assert.Throws<DeviceException>(() => switching.NoteSwitchOffLate(1.0, 1.05, Timing));

        Assert.Equal([false], run.Faults.Select(f => f.Recoverable));
        Assert.EndsWith("this frequency-only gate fired past the run's exit edge", run.Faults[0].Reason, StringComparison.Ordinal);
    }

    [Fact]
    public void KeepAliveWritten_OnAFreeWire_FreesTheWireAfterItsBytes()
    {
        var (switching, _, _) = Make(now: 1.0);

        switching.KeepAliveWritten(1.0, Timing);

        Assert.Equal(Timing.GateWireFreeAfter(1.0, double.NegativeInfinity, Timing.KeepAliveBytes), switching.WireFree);
    }

    private static (GateSwitching Switching, ILaserGate Gate, FakeRun Run) Make(double now, MachineProfile? profile = null)
    {
        var gate = Substitute.For<ILaserGate>();
        gate.LineWritten.Returns(Task.FromResult<long?>(null));
        var time = new FakeTimeProvider();
        var run = new FakeRun(now);
        var laser = new LaserSafety(gate, time, Timing.FrequencyHz, 1000, 20, new SafetyRun());
        return (new GateSwitching(gate, laser, time, profile ?? MachineProfile.Default, new Lock(), run), gate, run);
    }

    private sealed class SafetyRun : ILaserSafetyRun
    {
        public TimedSwitching Timing => GateSwitchingTests.Timing;

        public double GateQueueSeconds => 0;

        public void ThrowIfAborted()
        {
        }

        public void OffSequenceStarting(bool? inDoubt)
        {
        }

        public Task StopStageAsync() => Task.CompletedTask;
    }

    private sealed class FakeRun(double now) : IGateSwitchingRun
    {
        public List<(string Reason, bool Recoverable)> Faults { get; } = [];

        public double RunSeconds => now;

        public long EngravingStart => 0;

        public void ThrowIfEnded()
        {
        }

        public DeviceException Fault(string reason, bool recoverable)
        {
            Faults.Add((reason, recoverable));
            return new DeviceException(reason);
        }

        public Task DelayUntilAsync(double seconds, CancellationToken token) => Task.CompletedTask;
    }
}
