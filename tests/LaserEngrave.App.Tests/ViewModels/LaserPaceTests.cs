using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using NSubstitute;

namespace LaserEngrave.App.Tests.ViewModels;

/// <summary>The laser drawn at the machine's pace during a run: between the engine's reports, from the plan and the machine's clock only.</summary>
public sealed class LaserPaceTests
{
    private readonly ManualTimeProvider _clock = new();
    private readonly Fakes _fakes = new();
    private readonly IRunService _runs = Substitute.For<IRunService>();
    private readonly IRunLogStore _store = Substitute.For<IRunLogStore>();
    private readonly MachineActivity _activity = new();
    private readonly MachineViewModel _machine;
    private readonly JobViewModel _job;
    private readonly RunViewModel _run;

    public LaserPaceTests()
    {
        // The cross goes at the machine's clock: here the test's.
        _fakes.Connection.TimeProvider.Returns(_clock);
        _machine = new MachineViewModel(_fakes.Factory, MachineProfile.Default, _activity);
        _job = new JobViewModel(new ImageService(), MachineProfile.Default, _activity);
        var log = new LogViewModel(_store, Substitute.For<IFileAccess>(), _job);
        _run = new RunViewModel(_runs, _job, _machine, log, _clock);
        _store.History().Returns([]);
        _store.Save(Arg.Any<RunRecord>()).Returns(new RunLogFiles("/logs/run.json", "/logs/run.txt"));
    }

    [Fact]
    public async Task Run_BurnUnderWay_TheLaserMovesAlongItAtTheBurnSpeedBetweenReportsAndStopsAtItsEnd()
    {
        _job.LoadImage(TestFiles.Asset("qr-code.bmp"));
        _job.EditWidth(10);
        await _machine.ConnectCommand.ExecuteAsync(null);
        var moves = _job.Job!.Plan.Moves().ToList();
        var index = moves.FindIndex(m => m.Kind == MoveKind.Burn && m.LengthX >= 1000);
        var burn = moves[index];
        var perSecond = _job.BurnSpeedMmPerS * 1000 / MachineProfile.Default.X.MicrostepUm;
        var seconds = burn.LengthX / perSecond;
        var reported = new TaskCompletionSource<IProgress<EngraveProgress>>();
        var finish = new TaskCompletionSource();
        _runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(async c =>
            {
                var progress = c.Arg<IProgress<EngraveProgress>>();
                progress.Report(SessionResults.Report(RunState.Running, index, moves.Count, burn.Row, 41, x: burn.X0, y: burn.Y0, laserOn: true));
                reported.SetResult(progress);
                await finish.Task;
                return SessionResults.Ended(c.Arg<EngraveSession>(), SessionResults.Result(RunOutcome.Completed));
            });
        var run = _run.StartCommand.ExecuteAsync(null);
        var progress = await reported.Task.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);

        var atReport = _run.LaserMicrosteps;
        _clock.Advance(TimeSpan.FromSeconds(seconds / 2));
        var halfway = _run.LaserMicrosteps;
        _clock.Advance(TimeSpan.FromSeconds(seconds));
        var past = _run.LaserMicrosteps;
        progress.Report(SessionResults.Report(RunState.Paused, index + 1, moves.Count, burn.Row, 41, x: burn.X1, y: burn.Y1));
        _clock.Advance(TimeSpan.FromSeconds(seconds));
        var paused = _run.LaserMicrosteps;
        finish.SetResult();
        await run.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);

        Assert.Equal((burn.X0, burn.Y0), atReport);
        Assert.InRange(halfway!.Value.X, Math.Min(burn.X0, burn.X1) + (burn.LengthX / 2) - 60, Math.Min(burn.X0, burn.X1) + (burn.LengthX / 2) + 60);
        Assert.Equal(burn.Y0, halfway.Value.Y);
        Assert.Equal((burn.X1, burn.Y1), past);
        Assert.Equal((burn.X1, burn.Y1), paused);
        Assert.Null(_run.LaserMicrosteps);
        Assert.Equal(0, _clock.ActiveTimers);
    }

    [Fact]
    public void Now_RowsSecondBurnReportedAtTheRowsStart_FollowsTheBurnFromItsOwnStart()
    {
        // The engine reports the stage where the row began for the whole row (issue 36, finding 1): the cross snapped
        // back there at every report, 0.3-1.5 mm behind the machine.
        _job.LoadImage(TestFiles.Asset("qr-code.bmp"));
        _job.EditWidth(10);
        var job = _job.Job!;
        var moves = job.Plan.Moves().ToList();
        var first = moves.FindIndex(m => m.Kind == MoveKind.Burn);
        var index = moves.FindIndex(first + 1, m => m.Kind == MoveKind.Burn && m.Row == moves[first].Row && m.X0 != moves[first].X0);
        var burn = moves[index];
        var rowStart = moves.First(m => m.Row == burn.Row);
        var pace = new LaserPace(job, _clock);
        var seconds = burn.LengthX / (job.Spec.Process.BurnSpeedMmPerS * 1000 / MachineProfile.Default.X.MicrostepUm);

        pace.Report(1, index, rowStart.X0, rowStart.Y0);
        var atReport = pace.Now(moving: true)!.Value;
        _clock.Advance(TimeSpan.FromSeconds(seconds / 2));
        var halfway = pace.Now(moving: true)!.Value;

        Assert.Equal((burn.X0, burn.Y0), atReport);
        Assert.InRange(halfway.X, Math.Min(burn.X0, burn.X1) + (burn.LengthX / 2) - 60, Math.Min(burn.X0, burn.X1) + (burn.LengthX / 2) + 60);
    }

    [Fact]
    public void Now_EngineKnowsTheStrokeUnderWay_DrawsWhereTheEnginePutsTheStageUntilTheReportsPassIt()
    {
        // A timed raster's engine knows its row's one motion (flown gaps at the travel speed): the plan's moves do not.
        _job.LoadImage(TestFiles.Asset("qr-code.bmp"));
        _job.EditWidth(10);
        var job = _job.Job!;
        var moves = job.Plan.Moves().ToList();
        var index = moves.FindIndex(m => m.Kind == MoveKind.Burn);
        var burn = moves[index];
        long? askedAt = null;
        var engine = new StrokePosition(burn.X0 + 1234, burn.Y0, index, 3);
        var pace = new LaserPace(job, _clock, at =>
        {
            askedAt = at;
            return engine;
        });

        pace.Report(1, index, burn.X0, burn.Y0);
        _clock.Advance(TimeSpan.FromSeconds(0.25));
        var during = pace.Now(moving: true, out var atSeconds);
        pace.Report(1, index + 4, burn.X1, burn.Y1);
        var past = pace.Now(moving: true);

        Assert.Equal((burn.X0 + 1234, burn.Y0), during);
        Assert.Equal(_clock.GetTimestamp(), askedAt);
        Assert.Equal(_clock.GetTimestamp() / (double)_clock.TimestampFrequency, atSeconds);
        Assert.NotEqual((burn.X0 + 1234, burn.Y0), past);
    }

    [Fact]
    public void Now_TravelUnderWay_FollowsItsRampsAndArrivesAtItsEnd()
    {
        _job.LoadImage(TestFiles.Asset("qr-code.bmp"));
        _job.EditWidth(10);
        var job = _job.Job!;
        var moves = job.Plan.Moves().ToList();
        var index = moves.FindIndex(m => m.Kind == MoveKind.Travel && m.LengthY > 0);
        var travel = moves[index];
        var pace = new LaserPace(job, _clock);
        var perMm = 1000 / MachineProfile.Default.X.MicrostepUm;
        var length = Math.Max(travel.LengthX, travel.LengthY);
        var profile = new Core.Motion.TrapezoidProfile(length, job.Spec.Process.TravelSpeedMmPerS * perMm, job.Spec.Process.AccelerationMmPerS2 * perMm);

        Assert.Null(pace.Now(moving: true));
        pace.Report(1, index, travel.X0, travel.Y0);
        _clock.Advance(TimeSpan.FromSeconds(profile.RampTime / 2));
        var early = pace.Now(moving: true)!.Value;
        _clock.Advance(TimeSpan.FromSeconds(profile.Duration));
        var end = pace.Now(moving: true);

        // Half the ramp's time covers a quarter of the ramp's distance: slower than a straight line at the travel speed.
        var expected = profile.DistanceAt(profile.RampTime / 2) / length;
        Assert.Equal(travel.Y0 + ((travel.Y1 - travel.Y0) * expected), early.Y, 1.0);
        Assert.Equal((travel.X1, travel.Y1), end);
        Assert.Equal((travel.X0, travel.Y0), pace.Now(moving: false));
    }

    [Fact]
    public void Now_DrawingStrokeUnderWay_TravelsToItsRunUpThenFollowsItsPathToItsRest()
    {
        _job.OriginXMm = 5;
        _job.OriginYMm = 5;
        _job.WidthMm = 10;
        Assert.True(_job.LoadImage(TestFiles.Asset(Path.Combine("drawings", "hexagons.dxf"))));
        var drawing = _job.Drawing!;
        var (before, stroke) = (drawing.Schedule.Strokes[0], drawing.Schedule.Strokes[1]);
        var pace = new LaserPace(drawing, _clock);
        var perMm = 1000 / MachineProfile.Default.X.MicrostepUm;
        var travel = new Core.Motion.TrapezoidProfile(
            Math.Max(Math.Abs(stroke.RunUpStart.X - before.RestEnd.X), Math.Abs(stroke.RunUpStart.Y - before.RestEnd.Y)),
            drawing.Spec.Process.TravelSpeedMmPerS * perMm,
            drawing.Spec.Process.AccelerationMmPerS2 * perMm);

        pace.Report(1, 1, before.RestEnd.X, before.RestEnd.Y);
        var atReport = pace.Now(moving: true);
        _clock.Advance(TimeSpan.FromSeconds(travel.Duration));
        var atRunUp = pace.Now(moving: true);
        _clock.Advance(TimeSpan.FromSeconds(0.2));
        var burning = pace.Now(moving: true)!.Value;
        _clock.Advance(TimeSpan.FromSeconds(drawing.Schedule.EstimatedSeconds));
        var rested = pace.Now(moving: true);

        Assert.Equal((before.RestEnd.X, before.RestEnd.Y), atReport);
        Assert.Equal((stroke.RunUpStart.X, stroke.RunUpStart.Y), atRunUp);
        Assert.NotEqual((stroke.RunUpStart.X, stroke.RunUpStart.Y), burning);
        Assert.NotEqual((stroke.RestEnd.X, stroke.RestEnd.Y), burning);
        Assert.Equal((stroke.RestEnd.X, stroke.RestEnd.Y), rested);
    }

    [Fact]
    public void Now_DotJob_TravelsToTheNextDotAndStandsThere()
    {
        _job.LoadImage(TestFiles.Asset("qr-code.bmp"));
        _job.EditWidth(10);
        _job.Mode = PlanMode.Dots;
        var job = _job.Job!;
        var dots = job.Dots!.Dots().Take(2).ToList();
        var pace = new LaserPace(job, _clock);

        var perMm = 1000 / MachineProfile.Default.X.MicrostepUm;
        var travel = new Core.Motion.TrapezoidProfile(
            Math.Max(Math.Abs(dots[1].X - dots[0].X), Math.Abs(dots[1].Y - dots[0].Y)),
            job.Spec.Process.TravelSpeedMmPerS * perMm,
            job.Spec.Process.AccelerationMmPerS2 * perMm);

        pace.Report(1, 1, dots[0].X, dots[0].Y);
        _clock.Advance(TimeSpan.FromSeconds(travel.Duration / 2));
        var early = pace.Now(moving: true)!.Value;
        _clock.Advance(TimeSpan.FromSeconds(10));
        var there = pace.Now(moving: true);

        Assert.NotEqual((dots[0].X, dots[0].Y), early);
        Assert.NotEqual((dots[1].X, dots[1].Y), early);
        Assert.Equal((dots[1].X, dots[1].Y), there);
    }

    [Fact]
    public async Task Run_Drawing_TheLaserMovesBetweenTheEnginesStrokeReports()
    {
        _job.OriginXMm = 5;
        _job.OriginYMm = 5;
        _job.WidthMm = 10;
        Assert.True(_job.LoadImage(TestFiles.Asset(Path.Combine("drawings", "hexagons.dxf"))));
        await _machine.ConnectCommand.ExecuteAsync(null);
        var before = _job.Drawing!.Schedule.Strokes[0];
        var reported = new TaskCompletionSource();
        var finish = new TaskCompletionSource();
        _runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(async c =>
            {
                c.Arg<IProgress<EngraveProgress>>().Report(SessionResults.Report(RunState.Running, 1, _job.Drawing!.Schedule.Strokes.Count, 1, 2, x: before.RestEnd.X, y: before.RestEnd.Y));
                reported.SetResult();
                await finish.Task;
                return SessionResults.Ended(c.Arg<EngraveSession>(), SessionResults.Result(RunOutcome.Completed));
            });
        var run = _run.StartCommand.ExecuteAsync(null);
        await reported.Task.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);

        var atReport = _run.LaserMicrosteps;
        _clock.Advance(TimeSpan.FromSeconds(0.5));
        var later = _run.LaserMicrosteps;
        finish.SetResult();
        await run.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);

        Assert.Equal((before.RestEnd.X, before.RestEnd.Y), atReport);
        Assert.NotNull(later);
        Assert.NotEqual(atReport, later);
        Assert.Null(_run.LaserMicrosteps);
    }

    [Fact]
    public void Now_SecondPartUnderWay_ItsOwnMovesAtItsOwnBurnSpeed()
    {
        _job.LoadImage(TestFiles.Asset("qr-code.bmp"));
        _job.EditWidth(10);
        var sweep = new SweepViewModel(_job, _machine, _store, _clock) { Labels = false, Columns = string.Empty, Rows = "speed=0.5,2" };
        var plan = sweep.Plan!;
        var cell = plan.Cells[1].Job;
        var moves = cell.Plan.Moves().ToList();
        var index = moves.FindIndex(m => m.Kind == MoveKind.Burn && m.LengthX >= 1000);
        var burn = moves[index];
        var perSecond = 2 * 1000 / MachineProfile.Default.X.MicrostepUm;
        var pace = new LaserPace(LaserEngrave.Core.Sweeps.SweepJob.Of(plan), _clock);

        // The second cell (a sweep's part, as a layer of a job of layers) is reported: its burn, at its 2 mm/s.
        pace.Report(2, 1, index, burn.X0, burn.Y0);
        _clock.Advance(TimeSpan.FromSeconds(burn.LengthX / perSecond / 2));
        var halfway = pace.Now(moving: true)!.Value;

        Assert.InRange(halfway.X, Math.Min(burn.X0, burn.X1) + (burn.LengthX / 2) - 60, Math.Min(burn.X0, burn.X1) + (burn.LengthX / 2) + 60);
        Assert.Equal(burn.Y0, halfway.Y);
    }
}
