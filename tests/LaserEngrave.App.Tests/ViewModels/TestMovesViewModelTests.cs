using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using NSubstitute;
using NSubstitute.ExceptionExtensions;

namespace LaserEngrave.App.Tests.ViewModels;

public sealed class TestMovesViewModelTests
{
    private readonly Fakes _fakes = new();
    private readonly MachineViewModel _machine;
    private readonly JobViewModel _job;
    private readonly TestMovesViewModel _moves;

    public TestMovesViewModelTests()
    {
        _machine = new MachineViewModel(_fakes.Factory, MachineProfile.Default);
        _job = new JobViewModel(new ImageService(), MachineProfile.Default);
        _moves = new TestMovesViewModel(_machine, _job);
    }

    private async Task ConnectAsync()
    {
        await _machine.ConnectCommand.ExecuteAsync(null);
        Assert.True(_machine.IsConnected);
    }

    [Theory]
    [InlineData("x+", 1, 1008)]
    [InlineData("y+", 2, 1008)]
    public async Task Jog_Step100Um_MovesOneAxisByRoundedMicrosteps(string direction, int device, long expected)
    {
        await ConnectAsync();
        _moves.StepUm = 100;

        await _moves.JogCommand.ExecuteAsync(direction);

        var axis = device == 1 ? _fakes.X : _fakes.Y;
        await axis.Received(1).MoveAbsoluteAsync(expected, Arg.Any<CancellationToken>());
        Assert.Null(_moves.Error);
    }

    [Fact]
    public async Task Jog_BelowZero_RefusedWithoutMoving()
    {
        await ConnectAsync();
        _moves.StepUm = 10000;

        await _moves.JogCommand.ExecuteAsync("x-");

        Assert.Contains("outside the stage travel", _moves.Error, StringComparison.Ordinal);
        await _fakes.X.DidNotReceive().MoveAbsoluteAsync(Arg.Any<long>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Jog_UnknownDirection_ErrorAndNoMove()
    {
        await ConnectAsync();

        await _moves.JogCommand.ExecuteAsync("z+");

        Assert.Contains("z+", _moves.Error, StringComparison.Ordinal);
        await _fakes.X.DidNotReceive().MoveAbsoluteAsync(Arg.Any<long>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Jog_NotConnected_ErrorSaysConnectFirst()
    {
        await _moves.JogCommand.ExecuteAsync("x+");

        Assert.Contains("not connected", _moves.Error, StringComparison.Ordinal);
    }

    [Fact]
    public async Task GoTo_InsideTravel_BothAxesMoveLaserOffBeforeAndAfter()
    {
        await ConnectAsync();
        _moves.GoToXMm = 10;
        _moves.GoToYMm = 5;

        await _moves.GoToCommand.ExecuteAsync(null);

        Received.InOrder(() =>
        {
            _fakes.Gate.OffAsync(Arg.Any<CancellationToken>());
            _fakes.X.MoveAbsoluteAsync(100787, Arg.Any<CancellationToken>());
            _fakes.Gate.OffAsync(Arg.Any<CancellationToken>());
        });
        await _fakes.Y.Received(1).MoveAbsoluteAsync(50394, Arg.Any<CancellationToken>());
        Assert.Equal(100787, _machine.XMicrosteps);
    }

    [Fact]
    public async Task GoTo_OutsideTravel_ErrorAndNoMove()
    {
        await ConnectAsync();
        _moves.GoToXMm = 61;

        await _moves.GoToCommand.ExecuteAsync(null);

        Assert.Contains("61 mm is outside the stage travel", _moves.Error, StringComparison.Ordinal);
        await _fakes.X.DidNotReceive().MoveAbsoluteAsync(Arg.Any<long>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task GoToOrigin_NoJob_ErrorSaysOpenImage()
    {
        await ConnectAsync();

        await _moves.GoToOriginCommand.ExecuteAsync(null);

        Assert.Contains("no job planned", _moves.Error, StringComparison.Ordinal);
    }

    [Fact]
    public async Task Frame_Job_TracesTheFourEdges()
    {
        await ConnectAsync();
        _job.LoadImage(TestFiles.Asset("qr-code.bmp"));
        var g = _job.Job!.Geometry.Geometry;

        await _moves.FrameCommand.ExecuteAsync(null);

        Assert.Null(_moves.Error);
        await _fakes.X.Received(2).MoveAbsoluteAsync(g.EdgeX(0), Arg.Any<CancellationToken>());
        await _fakes.X.Received(1).MoveAbsoluteAsync(g.EdgeX(g.WidthPx), Arg.Any<CancellationToken>());
        await _fakes.Y.Received(1).MoveAbsoluteAsync(g.EdgeY(g.HeightPx), Arg.Any<CancellationToken>());
        await _fakes.Gate.DidNotReceive().SetFrequencyAsync(Arg.Any<int>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Frame_JobOutsideTravel_ErrorAndNoMove()
    {
        await ConnectAsync();
        _job.LoadImage(TestFiles.Asset("qr-code.bmp"));
        _job.OriginXMm = 58;

        await _moves.FrameCommand.ExecuteAsync(null);

        Assert.Contains("outside the stage travel", _moves.Error, StringComparison.Ordinal);
        await _fakes.X.DidNotReceive().MoveAbsoluteAsync(Arg.Any<long>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task TestFire_Pulses_BurstAtJobFrequency()
    {
        await ConnectAsync();
        _job.LaserFrequencyHz = 2000;
        _moves.TestFirePulses = 50;

        await _moves.TestFireCommand.ExecuteAsync(null);

        await _fakes.Gate.Received(1).BurstAsync(50, 2000, Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task TestFire_GateSilent_ErrorShown()
    {
        await ConnectAsync();
        _fakes.Gate.BurstAsync(Arg.Any<int>(), Arg.Any<int>(), Arg.Any<CancellationToken>()).ThrowsAsync(new DeviceTimeoutException("laser gate: no reply to BURST 100 1000 within 500 ms"));

        await _moves.TestFireCommand.ExecuteAsync(null);

        Assert.Contains("no reply to BURST", _moves.Error, StringComparison.Ordinal);
    }

    [Fact]
    public async Task Jog_RunActive_RefusedWithoutMoving()
    {
        await ConnectAsync();
        _moves.RunActive = true;

        await _moves.JogCommand.ExecuteAsync("x+");

        Assert.Contains("run is under way", _moves.Error, StringComparison.Ordinal);
        await _fakes.X.DidNotReceive().MoveAbsoluteAsync(Arg.Any<long>(), Arg.Any<CancellationToken>());
    }
}
