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
    private readonly MachineActivity _activity = new();
    private readonly MachineViewModel _machine;
    private readonly JobViewModel _job;
    private readonly TestMovesViewModel _moves;

    public TestMovesViewModelTests()
    {
        _machine = new MachineViewModel(_fakes.Factory, MachineProfile.Default, _activity);
        _job = new JobViewModel(new ImageService(), MachineProfile.Default, _activity);
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

            // After: the runs' own laser-off path, whose OFF nothing can hold up.
            _fakes.Gate.EmergencyAsync(EmergencyCommand.Off, Arg.Any<CancellationToken>());
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

        // The command line's goto says the same (issue 35: one rule for a position on the stage).
        Assert.Equal("go to X 61 mm: outside the travel 0..60 mm", _moves.Error);
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
    public async Task Frame_Drawing_TracesTheBoxAroundItsPlannedPaths()
    {
        await ConnectAsync();
        Assert.True(_job.LoadImage(TestFiles.Asset(Path.Combine("drawings", "hexagons.dxf"))));
        var points = _job.Drawing!.Plan.Paths.SelectMany(p => p.Points).ToList();
        var (left, top, right, bottom) = (points.Min(p => p.X), points.Min(p => p.Y), points.Max(p => p.X), points.Max(p => p.Y));
        Assert.True(_moves.FrameCommand.CanExecute(null));
        Assert.True(_moves.GoToOriginCommand.CanExecute(null));
        Assert.Null(_moves.JobMoveUnavailableReason);

        await _moves.FrameCommand.ExecuteAsync(null);

        Assert.Null(_moves.Error);
        await _fakes.X.Received(2).MoveAbsoluteAsync(left, Arg.Any<CancellationToken>());
        await _fakes.X.Received(1).MoveAbsoluteAsync(right, Arg.Any<CancellationToken>());
        await _fakes.Y.Received(1).MoveAbsoluteAsync(bottom, Arg.Any<CancellationToken>());
        await _fakes.Y.Received(2).MoveAbsoluteAsync(top, Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task GoToOrigin_Drawing_MovesToItsTopLeftCorner()
    {
        await ConnectAsync();
        _job.LoadImage(TestFiles.Asset(Path.Combine("drawings", "hexagons.dxf")));
        var points = _job.Drawing!.Plan.Paths.SelectMany(p => p.Points).ToList();

        await _moves.GoToOriginCommand.ExecuteAsync(null);

        Assert.Null(_moves.Error);
        await _fakes.X.Received(1).MoveAbsoluteAsync(points.Min(p => p.X), Arg.Any<CancellationToken>());
        await _fakes.Y.Received(1).MoveAbsoluteAsync(points.Min(p => p.Y), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Frame_NothingOpen_DisabledSayingWhy()
    {
        await ConnectAsync();

        Assert.False(_moves.FrameCommand.CanExecute(null));
        Assert.Equal("open an image or drawing first", _moves.JobMoveUnavailableReason);
    }

    [Fact]
    public async Task MotionText_FrameUnderWay_SaysSoUntilItEnds()
    {
        await ConnectAsync();
        _job.LoadImage(TestFiles.Asset("qr-code.bmp"));
        var release = new TaskCompletionSource<long>(TaskCreationOptions.RunContinuationsAsynchronously);
        _fakes.X.MoveAbsoluteAsync(Arg.Any<long>(), Arg.Any<CancellationToken>()).Returns(release.Task);

        var framing = _moves.FrameCommand.ExecuteAsync(null);
        await WaitUntil(() => _moves.MotionText is not null);

        Assert.Equal("Tracing the job's frame, laser off…", _moves.MotionText);
        release.SetResult(0);
        await framing;
        Assert.Null(_moves.MotionText);
    }

    [Fact]
    public async Task Frame_StageMoving_PositionReadWhileItMoves()
    {
        // A stage that takes 2 s of the machine's clock per move: the position is read meanwhile, not only at the end.
        var time = new ManualTimeProvider();
        _fakes.Connection.TimeProvider.Returns(time);
        await ConnectAsync();
        _job.LoadImage(TestFiles.Asset("qr-code.bmp"));
        var release = new TaskCompletionSource<long>(TaskCreationOptions.RunContinuationsAsynchronously);
        _fakes.X.MoveAbsoluteAsync(Arg.Any<long>(), Arg.Any<CancellationToken>()).Returns(release.Task);
        _fakes.X.GetPositionAsync(Arg.Any<CancellationToken>()).Returns(1234L);
        _fakes.X.ClearReceivedCalls();

        var framing = _moves.FrameCommand.ExecuteAsync(null);
        await WaitUntil(() => _moves.MotionText is not null);
        for (var i = 0; i < 3; i++)
        {
            await WaitUntil(() => time.ActiveTimers > 0);
            time.Advance(MachineViewModel.FollowInterval);
            await WaitUntil(() => _fakes.X.ReceivedCalls().Count(c => c.GetMethodInfo().Name == nameof(IStageAxis.GetPositionAsync)) > i);
        }

        Assert.Equal(1234L, _machine.XMicrosteps);
        release.SetResult(0);
        await framing;
        Assert.Null(_moves.Error);
    }

    private static async Task WaitUntil(Func<bool> condition)
    {
        // Waits for the move's task on the pool; what is asserted never depends on how long that takes.
        while (!condition())
        {
            await Task.Delay(5, TestContext.Current.CancellationToken);
        }
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
    public async Task TestFire_TwoHundredThousandPulses_FiredAsTheCommandLineFiresThem()
    {
        // Issue 35: the app once refused more than 100,000 pulses, which the command line fired (its range is the gate's burst range).
        var time = new ManualTimeProvider();
        _fakes.Connection.TimeProvider.Returns(time);
        await ConnectAsync();
        _job.LaserFrequencyHz = 1000;
        _moves.TestFirePulses = 200_000;

        var firing = _moves.TestFireCommand.ExecuteAsync(null);
        while (time.ActiveTimers == 0 && !firing.IsCompleted)
        {
            // The burst is sent, then the laser is left on its own for 200 s of the test's clock.
            await Task.Yield();
        }

        time.Advance(TimeSpan.FromSeconds(200));
        await firing;

        Assert.Null(_moves.TestFireProblem);
        Assert.Null(_moves.Error);
        await _fakes.Gate.Received(1).BurstAsync(200_000, 1000, Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task TestFire_MoreThanTheGatesBurstRange_RefusedWithTheRulesSentenceNothingSent()
    {
        await ConnectAsync();
        _moves.TestFirePulses = 1_000_001;

        await _moves.TestFireCommand.ExecuteAsync(null);

        Assert.Equal("test fire of 1000001 pulses: must be 1..1000000 pulses (the laser gate's burst range)", _moves.TestFireProblem);
        Assert.Equal(_moves.TestFireProblem, _moves.Error);
        await _fakes.Gate.DidNotReceive().BurstAsync(Arg.Any<int>(), Arg.Any<int>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Jog_StepOf100MmOnA150MmStage_MovesAsTheCommandLineWould()
    {
        // Issue 35: the app once held a jog step to 60,000 µm whatever the stage; the command line to the axis' travel.
        var wide = MachineProfile.Default with { X = MachineProfile.Default.X with { TravelMm = 150 } };
        _fakes.Connection.Profile.Returns(wide);
        _machine.Profile = wide;
        await ConnectAsync();
        _moves.StepUm = 100_000;

        await _moves.JogCommand.ExecuteAsync("x+");

        Assert.Null(_moves.Error);
        await _fakes.X.Received(1).MoveAbsoluteAsync(1_007_874, Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Jog_StepLongerThanTheAxisTravel_RefusedWithTheRulesSentence()
    {
        await ConnectAsync();
        _moves.StepUm = 70_000;

        await _moves.JogCommand.ExecuteAsync("y+");

        Assert.Equal("step 70000 µm: longer than the Y travel (60000 µm)", _moves.Error);
        await _fakes.Y.DidNotReceive().MoveAbsoluteAsync(Arg.Any<long>(), Arg.Any<CancellationToken>());
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
    public async Task Jog_RunUnderWay_RefusedSayingSoAndDisabled()
    {
        await ConnectAsync();
        using var run = _activity.Begin(MachineOperation.Run);

        Assert.False(_moves.JogCommand.CanExecute("x+"));
        Assert.False(_moves.GoToCommand.CanExecute(null));
        Assert.False(_moves.FrameCommand.CanExecute(null));
        Assert.False(_moves.TestFireCommand.CanExecute(null));
        await _moves.JogCommand.ExecuteAsync("x+");
        await _moves.TestFireCommand.ExecuteAsync(null);

        Assert.Contains("a run is under way", _moves.Error, StringComparison.Ordinal);
        await _fakes.X.DidNotReceive().MoveAbsoluteAsync(Arg.Any<long>(), Arg.Any<CancellationToken>());
        await _fakes.Gate.DidNotReceive().BurstAsync(Arg.Any<int>(), Arg.Any<int>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Jog_FivePressesWhileTheFirstMoves_StageEndsFiveStepsAway()
    {
        await ConnectAsync();
        var moving = new TaskCompletionSource();
        var arrive = new TaskCompletionSource();
        long position = 0;
        _fakes.X.GetPositionAsync(Arg.Any<CancellationToken>()).Returns(_ => position);
        _fakes.X.MoveAbsoluteAsync(Arg.Any<long>(), Arg.Any<CancellationToken>()).Returns(async c =>
        {
            moving.TrySetResult();
            await arrive.Task;
            return position = c.Arg<long>();
        });
        _moves.StepUm = 1000;

        var presses = new List<Task> { _moves.JogCommand.ExecuteAsync("x+") };
        await moving.Task.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);
        for (var i = 0; i < 4; i++)
        {
            Assert.True(_moves.JogCommand.CanExecute("x+"));
            presses.Add(_moves.JogCommand.ExecuteAsync("x+"));
        }

        Assert.False(_moves.GoToCommand.CanExecute(null));
        arrive.SetResult();
        await Task.WhenAll(presses).WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);

        Assert.Null(_moves.Error);
        Assert.Equal((long)Math.Round(5000 / MachineProfile.Default.X.MicrostepUm), position);
        Assert.Equal(position, _machine.XMicrosteps);
        Assert.False(_activity.IsBusy);
    }

    [Fact]
    public async Task GoTo_WhileJogging_RefusedSayingAJogIsUnderWay()
    {
        await ConnectAsync();
        var arrive = new TaskCompletionSource<long>();
        _fakes.X.MoveAbsoluteAsync(Arg.Any<long>(), Arg.Any<CancellationToken>()).Returns(arrive.Task);
        var jog = _moves.JogCommand.ExecuteAsync("x+");

        await _moves.GoToCommand.ExecuteAsync(null);

        Assert.Contains("a jog is under way", _moves.Error, StringComparison.Ordinal);
        arrive.SetResult(1008);
        await jog.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);
    }

    [Fact]
    public async Task Stop_WhileJogging_CancelledAndMachineFree()
    {
        await ConnectAsync();
        _fakes.X.MoveAbsoluteAsync(Arg.Any<long>(), Arg.Any<CancellationToken>())
            .Returns(async c =>
            {
                await Task.Delay(Timeout.Infinite, c.Arg<CancellationToken>());
                return 0L;
            });
        var jog = _moves.JogCommand.ExecuteAsync("x+");
        Assert.True(_activity.IsBusy);

        _moves.StopCommand.Execute(null);
        await jog.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);

        Assert.Equal("cancelled", _moves.Error);
        Assert.False(_activity.IsBusy);
    }
}
