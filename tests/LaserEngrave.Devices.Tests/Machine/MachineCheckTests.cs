using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Machine;
using NSubstitute;

namespace LaserEngrave.Devices.Tests.Machine;

/// <summary>The machine check on fakes of the interfaces the app and the command line both give it.</summary>
public sealed class MachineCheckTests
{
    private readonly IStageAxis _x = Axis(1);
    private readonly IStageAxis _y = Axis(2);
    private readonly IStage _stage = Substitute.For<IStage>();
    private readonly ILaserGate _gate = Substitute.For<ILaserGate>();
    private readonly ILatencyProbe _latency = Substitute.For<ILatencyProbe>();

    public MachineCheckTests()
    {
        _stage.X.Returns(_x);
        _stage.Y.Returns(_y);
        _gate.IdentifyAsync(Arg.Any<CancellationToken>()).Returns("PICGATE FAKE");
        _gate.GetStateAsync(Arg.Any<CancellationToken>()).Returns(new LaserGateState(0, false, 1000, true));
        var trips = RoundTrips.Of("fake", [14.0, 14.5], 12.5);
        _latency.MeasureAsync(Arg.Any<int>(), Arg.Any<CancellationToken>()).Returns(new LatencyMeasurement(trips, trips, trips with { WireMs = 13.5 }));
    }

    private MachineCheck Check() => new(_stage, _gate, _latency, MachineProfile.Default, TimeProvider.System, "COM4");

    [Fact]
    public async Task RunAsync_OnFakes_TellsEveryStepInOrderAsItEnds()
    {
        var told = new List<string>();

        var report = await Check().RunAsync(1, 10, tripWatchdog: false, TestContext.Current.CancellationToken, new Told<MachineCheckStep>(s => told.Add(s.Name)));

        Assert.Equal(MachineCheck.StepNames, told);
        Assert.Equal(MachineCheck.StepNames, report.Steps.Select(s => s.Name));
        Assert.Equal("PICGATE FAKE on COM4, switched off; found a counted-burst gate with a watchdog (it reports its state: watchdog 1000 ms)", report.Steps[0].Finding);
        Assert.StartsWith("device 1 (X) sent to 10079 microsteps", report.Steps.Single(s => s.Name == "X move").Finding, StringComparison.Ordinal);
        Assert.Equal(MachineCheckResult.Skipped, report.Steps[^1].Result);
    }

    [Fact]
    public async Task RunAsync_StoppedWhileHoming_BothAxesStopAndTheLaserIsSwitchedOff()
    {
        using var stop = CancellationTokenSource.CreateLinkedTokenSource(TestContext.Current.CancellationToken);
        _x.HomeAsync(Arg.Any<CancellationToken>()).Returns(async c =>
        {
            await stop.CancelAsync();
            await Task.Delay(Timeout.Infinite, c.Arg<CancellationToken>());
            return 0L;
        });

        await Assert.ThrowsAnyAsync<OperationCanceledException>(() => Check().RunAsync(1, 10, tripWatchdog: true, stop.Token));

        await _x.Received(1).StopAsync(CancellationToken.None);
        await _y.Received(1).StopAsync(CancellationToken.None);
        await _gate.Received().OffAsync(CancellationToken.None);
        await _gate.DidNotReceive().SetFrequencyAsync(Arg.Any<int>(), Arg.Any<CancellationToken>());
    }

    private static IStageAxis Axis(byte number)
    {
        var axis = Substitute.For<IStageAxis>();
        long position = 0;
        axis.DeviceNumber.Returns(number);
        axis.IdentifyAsync(Arg.Any<CancellationToken>()).Returns(new AxisIdentity(number, 4212, 523, 0x80, 604724));
        axis.GetPositionAsync(Arg.Any<CancellationToken>()).Returns(_ => position);
        axis.MoveAbsoluteAsync(Arg.Any<long>(), Arg.Any<CancellationToken>()).Returns(c => position = c.Arg<long>());
        axis.HomeAsync(Arg.Any<CancellationToken>()).Returns(_ => position = 0);
        return axis;
    }

    private sealed class Told<T>(Action<T> report) : IProgress<T>
    {
        public void Report(T value) => report(value);
    }
}
