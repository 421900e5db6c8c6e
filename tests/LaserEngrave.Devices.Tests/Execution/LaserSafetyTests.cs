using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Devices.Tests.Fakes;
using LaserEngrave.Simulator.Timing;
using Microsoft.Extensions.Time.Testing;
using NSubstitute;
using NSubstitute.ExceptionExtensions;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>The laser's safety alone (<see cref="LaserSafety"/>): the off sequence on abort and fault against a fake gate.</summary>
public class LaserSafetyTests
{
    private const int WatchdogMs = 1000;

    [Fact(Timeout = 60_000)]
    public async Task OffSafelyAsync_GateAcknowledges_ConfirmsOffByOffAndLeavesTheStage()
    {
        var gate = Substitute.For<ILaserGate>();
        var run = new FakeRun();
        var laser = new LaserSafety(gate, new FakeTimeProvider(), 1000, WatchdogMs, 20, run);

        await laser.OffSafelyAsync();

        Assert.Equal(LaserOffPath.Off, laser.OffState.By);
        Assert.True(laser.OffConfirmed);
        Assert.Null(laser.OffState.Problem);
        Assert.Equal(0, run.Stops);
        Assert.Equal([false], run.Starts);
        await gate.Received(1).EmergencyAsync(EmergencyCommand.Off, Arg.Any<CancellationToken>());
        await gate.DidNotReceive().EmergencyAsync(EmergencyCommand.FrequencyZero, Arg.Any<CancellationToken>());
        await gate.DidNotReceiveWithAnyArgs().SetFrequencyAsync(Arg.Any<int>(), Arg.Any<CancellationToken>());
    }

    [Fact(Timeout = 60_000)]
    public async Task OffSafelyAsync_AfterARefusedSwitchOff_TakesEveryPathAtOnceAndStopsTheStage()
    {
        var gate = Substitute.For<ILaserGate>();
        gate.EmergencyAsync(EmergencyCommand.Off, Arg.Any<CancellationToken>()).ThrowsAsync(new DeviceException("laser gate replied 'ERR'"));
        var run = new FakeRun();
        var laser = new LaserSafety(gate, new FakeTimeProvider(), 1000, WatchdogMs, 20, run);
        laser.MarkSwitchOffFailed();

        await laser.OffSafelyAsync();

        Assert.Equal(LaserOffPath.FrequencyZero, laser.OffState.By);
        Assert.True(laser.OffConfirmed);
        Assert.Equal(1, run.Stops);
        Assert.Equal([true], run.Starts);
        await gate.Received(1).EmergencyAsync(EmergencyCommand.Off, Arg.Any<CancellationToken>());
        await gate.Received(1).EmergencyAsync(EmergencyCommand.FrequencyZero, Arg.Any<CancellationToken>());
        await gate.Received(1).EmergencyAsync(EmergencyCommand.ShortestWatchdog, Arg.Any<CancellationToken>());
    }

    [Fact(Timeout = 60_000)]
    public async Task OffSafelyAsync_NeitherOffNorFrequencyZeroAcknowledged_ClosesTheGatesPortAndSaysAPersonMustCheck()
    {
        var gate = Substitute.For<ILaserGate>();
        gate.EmergencyAsync(EmergencyCommand.Off, Arg.Any<CancellationToken>()).ThrowsAsync(new DeviceException("laser gate did not acknowledge 'OFF' within 500 ms"));
        gate.EmergencyAsync(EmergencyCommand.FrequencyZero, Arg.Any<CancellationToken>()).ThrowsAsync(new DeviceException("laser gate did not acknowledge 'FREQ 0' within 500 ms"));
        gate.EmergencyAsync(EmergencyCommand.ShortestWatchdog, Arg.Any<CancellationToken>()).ThrowsAsync(new DeviceException("laser gate did not acknowledge 'WDOG 50' within 500 ms"));
        var run = new FakeRun();
        var laser = new LaserSafety(gate, new FakeTimeProvider(), 1000, WatchdogMs, 20, run);

        await laser.OffSafelyAsync();
        await laser.OffSafelyAsync();

        Assert.Equal(LaserOffPath.None, laser.OffState.By);
        Assert.False(laser.OffConfirmed);
        Assert.Contains("its watchdog (1000 ms) switches the laser off; a person must check the laser", laser.OffState.Problem, StringComparison.Ordinal);
        await gate.Received(1).CloseAsync();
        Assert.Equal(1, run.Stops);
        Assert.Equal([false, null], run.Starts);
        await gate.Received(2).EmergencyAsync(EmergencyCommand.Off, Arg.Any<CancellationToken>());
    }

    [Fact(Timeout = 60_000)]
    public async Task OffSafelyAsync_OffUnansweredWithinItsRoundTrip_TakesEveryPathAndAcceptsTheLateAnswer()
    {
        using var time = new VirtualTimeProvider();
        var gate = Substitute.For<ILaserGate>();
        var late = new TaskCompletionSource();
        gate.EmergencyAsync(EmergencyCommand.Off, Arg.Any<CancellationToken>()).Returns(late.Task, Task.FromException(new DeviceException("laser gate did not acknowledge 'OFF' within 500 ms")));
        gate.EmergencyAsync(EmergencyCommand.FrequencyZero, Arg.Any<CancellationToken>()).Returns(_ =>
        {
            late.TrySetResult();
            return Task.FromException(new DeviceException("laser gate did not acknowledge 'FREQ 0' within 500 ms"));
        });
        var run = new FakeRun();
        var laser = new LaserSafety(gate, time, 1000, WatchdogMs, 20, run);

        await time.RunTestAsync(laser.OffSafelyAsync);

        Assert.Equal(LaserOffPath.OffAgain, laser.OffState.By);
        Assert.True(laser.OffConfirmed);
        Assert.Equal(1, run.Stops);
    }

    [Fact(Timeout = 60_000)]
    public async Task SwitchAsync_OnAfterAnAbort_SendsNothing()
    {
        var gate = Substitute.For<ILaserGate>();
        var run = new FakeRun { Aborted = true };
        var laser = new LaserSafety(gate, new FakeTimeProvider(), 1000, WatchdogMs, 20, run);
        laser.StartKeepAlive(TimeSpan.FromMilliseconds(250), whileOn: true, _ => { });

        await Assert.ThrowsAsync<OperationCanceledException>(() => laser.SwitchAsync(on: true));

        Assert.False(laser.On);
        await gate.DidNotReceiveWithAnyArgs().SetFrequencyAsync(Arg.Any<int>(), Arg.Any<CancellationToken>());
        await laser.DisposeAsync();
    }

    [Fact(Timeout = 60_000)]
    public async Task SwitchAsync_OnThenOff_CountsTheTimeTheLaserWasOn()
    {
        var time = new FakeTimeProvider();
        var gate = Substitute.For<ILaserGate>();
        var laser = new LaserSafety(gate, time, 1000, WatchdogMs, 20, new FakeRun());
        laser.StartKeepAlive(TimeSpan.FromMilliseconds(250), whileOn: false, _ => { });

        await laser.SwitchAsync(on: true);
        Assert.True(laser.On);
        time.Advance(TimeSpan.FromSeconds(1.5));
        await laser.SwitchAsync(on: false);

        Assert.False(laser.On);
        Assert.Equal(1.5, laser.OnSeconds, 9);
        await gate.Received(1).SetFrequencyAsync(1000, Arg.Any<CancellationToken>());
        await laser.DisposeAsync();
    }

    /// <summary>The run a <see cref="LaserSafety"/> guards: counts the stage stops and the off sequences started.</summary>
    private sealed class FakeRun : ILaserSafetyRun
    {
        public bool Aborted { get; init; }

        public int Stops { get; private set; }

        public List<bool?> Starts { get; } = [];

        public TimedSwitching Timing { get; } = TimedSwitching.For(ProcessSettings.Default, MachineProfile.Default, MachineProfile.Default.X.MicrostepUm);

        public double GateQueueSeconds { get; init; }

        public void ThrowIfAborted()
        {
            if (Aborted)
            {
                throw new OperationCanceledException("aborted");
            }
        }

        public void OffSequenceStarting(bool? inDoubt) => Starts.Add(inDoubt);

        public Task StopStageAsync()
        {
            Stops++;
            return Task.CompletedTask;
        }
    }
}
