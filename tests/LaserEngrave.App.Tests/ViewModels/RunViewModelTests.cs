using LaserEngrave.App.Services;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;
using NSubstitute;
using LaserEngrave.Devices.Execution;
using NSubstitute.Core;

namespace LaserEngrave.App.Tests.ViewModels;

public sealed class RunViewModelTests
{
    private readonly Fakes _fakes = new();
    private readonly IRunService _runs = Substitute.For<IRunService>();
    private readonly IRunLogStore _store = Substitute.For<IRunLogStore>();
    private readonly MachineActivity _activity = new();
    private readonly MachineViewModel _machine;
    private readonly JobViewModel _job;
    private readonly LogViewModel _log;
    private readonly RunViewModel _run;

    public RunViewModelTests()
    {
        _machine = new MachineViewModel(_fakes.Factory, MachineProfile.Default, _activity);
        _job = new JobViewModel(new ImageService(), MachineProfile.Default, _activity);
        _log = new LogViewModel(_store, Substitute.For<IFileAccess>(), _job);
        _run = new RunViewModel(_runs, _job, _machine, _log, TimeProvider.System);
        _store.History().Returns([]);
        _store.Save(Arg.Any<RunRecord>()).Returns(new RunLogFiles("/logs/run.json", "/logs/run.txt"));
    }

    private static RunResult Result(RunOutcome outcome, string? fault = null) => SessionResults.Result(outcome, fault);

    private static EngraveResult Ended(EngraveSession session, RunResult? run, Exception? error = null) => SessionResults.Ended(session, run, error);

    private static Func<CallInfo, Task<EngraveResult>> Ends(RunResult run) => SessionResults.Ends(run);

    private static EngraveProgress Report(RunState state, long movesDone, long movesTotal, int rowsDone, int rowsTotal, int pass = 1, int passes = 1, long x = 0, long y = 0, bool laserOn = false, double remainingSeconds = 0) =>
        SessionResults.Report(state, movesDone, movesTotal, rowsDone, rowsTotal, pass, passes, x, y, laserOn, remainingSeconds);

    private async Task ReadyAsync()
    {
        _job.LoadImage(TestFiles.Asset("qr-code.bmp"));
        await _machine.ConnectCommand.ExecuteAsync(null);
    }

    [Fact]
    public async Task Start_AllWhiteImage_RefusedNamingTheFileAndNoRun()
    {
        using var folder = TestFiles.NewFolder();
        var white = Path.Combine(folder.Path, "white.bmp");
        using (var file = File.Create(white))
        {
            Core.Imaging.BmpMaskWriter.Write(file, new Core.Imaging.BitMask(8, 6));
        }

        _job.LoadImage(white);
        await _machine.ConnectCommand.ExecuteAsync(null);

        await _run.StartNowAsync();

        // The words the command line and the API give: the file, then what is wrong with it.
        Assert.StartsWith($"{white}: the mask has no pixel to burn", _run.Error, StringComparison.Ordinal);
        Assert.Equal(RunState.Failed, _run.State);
        Assert.Equal(_run.Error, _run.StartRefusal());
        await _runs.DidNotReceive().RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Start_NoImage_ErrorAndNoRun()
    {
        await _machine.ConnectCommand.ExecuteAsync(null);

        await _run.StartCommand.ExecuteAsync(null);

        Assert.Contains("no job planned", _run.Error, StringComparison.Ordinal);
        await _runs.DidNotReceive().RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Start_LogFolderFull_ErrorNamingItAndNoRun()
    {
        await ReadyAsync();
        _store.When(s => s.CheckWritable()).Do(_ => throw new RunLogException("/logs: cannot write the run log there: No space left on device"));

        await _run.StartCommand.ExecuteAsync(null);

        Assert.Equal("/logs: cannot write the run log there: No space left on device", _run.Error);
        Assert.Equal(RunState.Failed, _run.State);
        await _runs.DidNotReceive().RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Start_NotConnected_ErrorAndNoRun()
    {
        _job.LoadImage(TestFiles.Asset("qr-code.bmp"));

        await _run.StartCommand.ExecuteAsync(null);

        Assert.Contains("not connected", _run.Error, StringComparison.Ordinal);
        await _runs.DidNotReceive().RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Start_JobOutsideTravel_ErrorAndNoRun()
    {
        await ReadyAsync();
        _job.OriginYMm = 57;

        await _run.StartCommand.ExecuteAsync(null);

        // The job rules' sentence, as the origin field and the command line say it (issue 35).
        Assert.Contains("does not fit the stage's travel (60 x 60 mm): move the origin or make it smaller", _run.Error, StringComparison.Ordinal);
        await _runs.DidNotReceive().RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Start_TurnedAndMirroredJob_TheSessionRunsTheTurnedMaskAndTheLogKeepsTheTurn()
    {
        await ReadyAsync();
        Assert.True(_job.LoadImage(TestFiles.Asset("text-banner.png")));
        _job.Rotate(clockwise: true);
        _job.FlipHorizontal();
        var turned = _job.Mask!;
        EngraveSession? ran = null;
        _runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(c =>
            {
                ran = c.Arg<EngraveSession>();
                return Task.FromResult(Ended(ran, Result(RunOutcome.Completed)));
            });

        await _run.StartCommand.ExecuteAsync(null);

        Assert.NotNull(ran);
        Assert.Equal((60, 308), (turned.Width, turned.Height));
        Assert.True(ran.Job!.Mask.ContentEquals(turned));
        _store.Received(1).Save(Arg.Is<RunRecord>(r => r.Mask.QuarterTurns == 1 && r.Mask.MirrorY && !r.Mask.MirrorX && r.Image.WidthPx == 60));
    }

    [Fact]
    public async Task Start_RunCompletes_CompletedAndLogged()
    {
        await ReadyAsync();
        _log.SampleId = "S-17";
        _log.Notes = "first try";
        _runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(c =>
            {
                c.Arg<IProgress<EngraveProgress>>().Report(Report(RunState.Running, 10, 10, 5, 5, x: 123, y: 456));
                return Task.FromResult(Ended(c.Arg<EngraveSession>(), Result(RunOutcome.Completed)));
            });

        await _run.StartCommand.ExecuteAsync(null);

        Assert.Equal(RunState.Completed, _run.State);
        Assert.Equal(1, _run.Fraction);
        Assert.Equal(123, _run.Progress!.Run.XMicrosteps);
        _store.Received(1).Save(Arg.Is<RunRecord>(r => r.Outcome == RunOutcome.Completed && r.SampleId == "S-17" && r.Notes == "first try" && r.RunsDone == 7));
        Assert.Equal(RunOutcome.Completed, _log.LastRun!.Record!.Outcome);
    }

    private async Task DrawingReadyAsync()
    {
        _job.OriginXMm = 5;
        _job.OriginYMm = 5;
        _job.WidthMm = 10;
        _job.LoadImage(TestFiles.Asset(Path.Combine("drawings", "hexagons.dxf")));
        await _machine.ConnectCommand.ExecuteAsync(null);
    }

    [Fact]
    public async Task Start_Drawing_RunsItsSessionAndLogsTheDrawing()
    {
        await DrawingReadyAsync();
        var sessions = new List<EngraveSession>();
        _runs.RunAsync(Arg.Do<EngraveSession>(sessions.Add), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(Ends(Result(RunOutcome.Completed)));

        Assert.True(_run.CanStart);
        await _run.StartCommand.ExecuteAsync(null);

        Assert.Same(_job.Drawing, Assert.Single(sessions).Drawing);
        Assert.Equal(RunState.Completed, _run.State);
        _store.Received(1).Save(Arg.Is<RunRecord>(r => r.Drawing != null && r.Drawing.Strokes == _job.Drawing!.Schedule.Strokes.Count));
    }

    [Fact]
    public async Task CanStart_GateWithoutWatchdogNotAccepted_FalseUntilTickedThenTheSessionCarriesIt()
    {
        await DrawingReadyAsync();
        var sessions = new List<EngraveSession>();
        _runs.RunAsync(Arg.Do<EngraveSession>(sessions.Add), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(Ends(Result(RunOutcome.Completed)));
        Assert.True(_run.CanStart);

        _machine.Profile = MachineProfile.Load(TestFiles.Asset(Path.Combine("profiles", "frequency-only.json")));
        Assert.False(_run.CanStart);
        _machine.AcceptNoWatchdog = true;
        Assert.True(_run.CanStart);
        await _run.StartCommand.ExecuteAsync(null);

        Assert.True(Assert.Single(sessions).Options.AcceptNoWatchdog);
    }

    [Fact]
    public async Task CanStart_DrawingWithABadChordTolerance_IsFalseAndNoSessionRuns()
    {
        await DrawingReadyAsync();
        Assert.True(_run.CanStart);

        _job.ToleranceUm = 5000;

        Assert.False(_run.CanStart);
        Assert.False(_run.StartCommand.CanExecute(null));
        await _run.StartCommand.ExecuteAsync(null);
        await _runs.DidNotReceive().RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Start_Layers_RunsOneSessionOfEveryLayerAndSaysWhichLayerIsUnderWay()
    {
        using var folder = TestFiles.NewFolder();
        var layers = new LayersViewModel(new JobFiles(new AppFolders(folder.Path)), _job, _activity);
        var run = new RunViewModel(_runs, _job, _machine, _log, TimeProvider.System, layers);
        Assert.True(layers.Open(TestFiles.Asset(Path.Combine("jobs", "plate.json"))));
        await _machine.ConnectCommand.ExecuteAsync(null);
        string? layerText = null;
        var sessions = new List<EngraveSession>();
        _runs.RunAsync(Arg.Do<EngraveSession>(sessions.Add), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(c =>
            {
                c.Arg<IProgress<EngraveProgress>>().Report(Report(RunState.Running, 10, 100, 2, 41, pass: 2, passes: 4) with { Layer = 2 });
                layerText = run.Bar.LayerText;
                return Task.FromResult(Ended(c.Arg<EngraveSession>(), Result(RunOutcome.Completed)));
            });

        Assert.True(run.RunsLayers);
        Assert.True(run.CanStart);
        await run.StartCommand.ExecuteAsync(null);

        var session = Assert.Single(sessions);
        Assert.Equal(4, session.Passes);
        Assert.Same(((DrawingPart)layers.Job!.Layers[0]).Drawing, session.Drawing);
        Assert.Equal("layer 2 of 3 “logo”", layerText);
        Assert.Equal(RunState.Completed, run.State);
        Assert.Equal(Path.GetFullPath(TestFiles.Asset(Path.Combine("jobs", "plate.json"))), session.Options.JobFile);
    }

    [Fact]
    public async Task Continue_LayersAbortedInLayerTwo_GoesOnFromThatLayersStopPointAsTheCommandLineWould()
    {
        using var folder = TestFiles.NewFolder();
        var layers = new LayersViewModel(new JobFiles(new AppFolders(folder.Path)), _job, _activity);
        var run = new RunViewModel(_runs, _job, _machine, _log, TimeProvider.System, layers);
        layers.Open(TestFiles.Asset(Path.Combine("jobs", "plate.json")));
        await _machine.ConnectCommand.ExecuteAsync(null);
        var stop = new RunStopPoint(12, 140);
        var sessions = new List<EngraveSession>();
        _runs.RunAsync(Arg.Do<EngraveSession>(sessions.Add), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(
                c =>
                {
                    var ended = Ended(c.Arg<EngraveSession>(), Result(RunOutcome.Aborted) with { StopPoint = stop });
                    var logged = layers.Job!.Layers.Select((l, i) => new RunLayer(l.Layer.Name, l.Layer.Source, "0", l.Layer.Mode, l.Layer.DrawingLayer, 1, 1, 0, 0, 1, 1000, l.Layer.Passes)
                    {
                        PassesDone = i == 0 ? 1 : 0,
                        Outcome = i switch { 0 => RunOutcome.Completed, 1 => RunOutcome.Aborted, _ => null },
                    });
                    return Task.FromResult(ended with { Record = ended.Record with { Layers = [.. logged] } });
                },
                Ends(Result(RunOutcome.Completed)));
        await run.StartCommand.ExecuteAsync(null);
        Assert.True(run.CanContinue);

        layers.Update(2, layers.Layers[2] with { Passes = 3 });
        Assert.Contains("the layers changed since the run stopped", run.ContinueUnavailableReason, StringComparison.Ordinal);
        layers.Update(2, layers.Layers[2] with { Passes = 2 });
        Assert.True(run.CanContinue);
        await run.ContinueCommand.ExecuteAsync(null);

        Assert.Equal(2, sessions.Count);
        Assert.Equal(new LayerResumePoint(1, 0, stop), sessions[1].Options.ResumeLayers);
        Assert.Null(sessions[1].Options.ResumeFrom);
        Assert.Equal(3, sessions[1].Passes);
        Assert.Equal(RunState.Completed, run.State);
    }

    [Fact]
    public async Task Continue_DrawingAborted_GoesOnFromItsStopPoint()
    {
        await DrawingReadyAsync();
        var stop = new RunStopPoint(7, 7);
        var sessions = new List<EngraveSession>();
        _runs.RunAsync(Arg.Do<EngraveSession>(sessions.Add), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(Ends(Result(RunOutcome.Aborted) with { StopPoint = stop }), Ends(Result(RunOutcome.Completed)));
        await _run.StartCommand.ExecuteAsync(null);
        Assert.True(_run.CanContinue);

        await _run.ContinueCommand.ExecuteAsync(null);

        Assert.Same(_job.Drawing, sessions[1].Drawing);
        Assert.Equal(stop, sessions[1].Options.ResumeFrom);
        Assert.Equal(RunState.Completed, _run.State);
    }

    [Fact]
    public async Task CanStart_LayerWithABadValue_IsFalseEvenWithAPlannedSingleJob()
    {
        using var folder = TestFiles.NewFolder();
        var layers = new LayersViewModel(new JobFiles(new AppFolders(folder.Path)), _job, _activity);
        var run = new RunViewModel(_runs, _job, _machine, _log, TimeProvider.System, layers);
        await ReadyAsync();
        layers.Open(TestFiles.Asset(Path.Combine("jobs", "plate.json")));
        Assert.True(run.CanStart);

        layers.Update(2, layers.Layers[2] with { Origin = new OriginMm(59, 10) });

        Assert.Contains("layer \"cut\" does not fit the stage's travel", layers.Error, StringComparison.Ordinal);
        Assert.False(run.CanStart);
        layers.Clear();
        Assert.True(run.CanStart);
        Assert.False(run.RunsLayers);
    }

    [Fact]
    public async Task Start_TwoPassesCompleted_LogSaysBothPassesDone()
    {
        await ReadyAsync();
        _job.Passes = 2;
        var sessions = new List<EngraveSession>();
        _runs.RunAsync(Arg.Do<EngraveSession>(sessions.Add), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(Ends(Result(RunOutcome.Completed)));

        await _run.StartCommand.ExecuteAsync(null);

        Assert.Equal(2, Assert.Single(sessions).Job!.Spec.Passes);
        Assert.Equal(2, sessions[0].Passes);
        _store.Received(1).Save(Arg.Is<RunRecord>(r => r.Passes == 2 && r.PassesDone == 2));
    }

    [Fact]
    public async Task Continue_AfterAFault_RunsTheRestFromTheStopPointAndLogsItAsResumed()
    {
        await ReadyAsync();
        _job.Passes = 2;
        var stop = new RunStopPoint(12, 140, 5000, 6000);
        var sessions = new List<EngraveSession>();
        _runs.RunAsync(Arg.Do<EngraveSession>(sessions.Add), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(Ends(Result(RunOutcome.Failed, "x axis: no reply") with { StopPoint = stop }), Ends(Result(RunOutcome.Completed)));
        await _run.StartCommand.ExecuteAsync(null);
        Assert.True(_run.CanContinue);

        await _run.ContinueCommand.ExecuteAsync(null);

        Assert.Equal(RunState.Completed, _run.State);
        Assert.Equal([null, stop], sessions.Select(r => r.Options.ResumeFrom));
        Assert.Equal(1, sessions[1].Passes);
        _store.Received(1).Save(Arg.Is<RunRecord>(r => r.Resumed && r.Outcome == RunOutcome.Completed));
        Assert.False(_run.CanContinue);
    }

    [Fact]
    public async Task Continue_JobChangedSinceTheStop_RefusedAndNothingRuns()
    {
        await ReadyAsync();
        _runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(Ends(Result(RunOutcome.Failed, "x axis: no reply") with { StopPoint = new RunStopPoint(3, 20, null, null) }));
        await _run.StartCommand.ExecuteAsync(null);
        _job.OriginXMm = 7;

        await _run.ContinueCommand.ExecuteAsync(null);

        Assert.Contains("the job changed", _run.Error, StringComparison.Ordinal);
        Assert.False(_run.CanContinue);
        await _runs.Received(1).RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task RunBar_AnotherImageOpenedAfterACompletedRun_BackToIdle()
    {
        await ReadyAsync();
        _runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>()).Returns(Ends(Result(RunOutcome.Completed)));
        await _run.StartCommand.ExecuteAsync(null);
        Assert.Equal(RunState.Completed, _run.State);

        _job.LoadImage(TestFiles.Asset("text-banner.png"));

        Assert.Equal((RunState.Idle, 0.0), (_run.State, _run.Fraction));
    }

    [Fact]
    public async Task RunBar_JobChangedAfterAFailedRun_ItsErrorGoesTheStopPointStays()
    {
        await ReadyAsync();
        _runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(Ends(Result(RunOutcome.Failed, "laser gate: no reply to FREQ 1000 within 500 ms")));
        await _run.StartCommand.ExecuteAsync(null);
        Assert.NotNull(_run.Error);

        _job.EditWidth(4);

        Assert.Null(_run.Error);
        Assert.Equal(RunState.Idle, _run.State);
    }

    [Fact]
    public async Task RunBar_LayersRunCompletedThenTheLayersCleared_BackToIdle()
    {
        using var folder = TestFiles.NewFolder();
        var layers = new LayersViewModel(new JobFiles(new AppFolders(folder.Path)), _job, _activity);
        var run = new RunViewModel(_runs, _job, _machine, _log, TimeProvider.System, layers);
        Assert.True(layers.Open(TestFiles.Asset(Path.Combine("jobs", "plate.json"))));
        await _machine.ConnectCommand.ExecuteAsync(null);
        _runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>()).Returns(Ends(Result(RunOutcome.Completed)));
        await run.StartCommand.ExecuteAsync(null);
        Assert.Equal(RunState.Completed, run.State);

        layers.Clear();

        Assert.Equal((RunState.Idle, 0.0), (run.State, run.Fraction));
    }

    [Fact]
    public async Task StageBurned_SingleJobRunThenAJobOfLayersOpened_NothingOfTheLayersDrawnBurned()
    {
        // Issue 36, finding 9: the plate's marks layer was drawn in the "burned" colour before anything burned, the last
        // single run's progress read as the new layers'.
        using var folder = TestFiles.NewFolder();
        var layers = new LayersViewModel(new JobFiles(new AppFolders(folder.Path)), _job, _activity);
        var run = new RunViewModel(_runs, _job, _machine, _log, TimeProvider.System, layers);
        await ReadyAsync();
        _runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(c =>
            {
                c.Arg<IProgress<EngraveProgress>>().Report(Report(RunState.Running, 10, 10, 5, 5));
                return Task.FromResult(Ended(c.Arg<EngraveSession>(), Result(RunOutcome.Completed)));
            });
        await run.StartCommand.ExecuteAsync(null);
        Assert.NotNull(run.Progress);

        Assert.True(layers.Open(TestFiles.Asset(Path.Combine("jobs", "plate.json"))));

        Assert.Null(run.Progress);
        Assert.True(run.RunsLayers);
    }

    [Fact]
    public async Task Start_GateSilentDuringRun_FailedWithErrorAndLogged()
    {
        await ReadyAsync();
        _runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(Ends(Result(RunOutcome.Failed, "laser gate: no reply to FREQ 1000 within 500 ms")));

        await _run.StartCommand.ExecuteAsync(null);

        Assert.Equal(RunState.Failed, _run.State);
        Assert.Contains("no reply to FREQ", _run.Error, StringComparison.Ordinal);
        _store.Received(1).Save(Arg.Is<RunRecord>(r => r.Outcome == RunOutcome.Failed && r.Fault!.Message.Contains("FREQ")));
    }

    [Fact]
    public async Task Start_PreflightRefuses_RefusedWithReasonAndLogged()
    {
        await ReadyAsync();
        _runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(c => Task.FromResult(Ended(c.Arg<EngraveSession>(), null, new PreflightException("stage: device 1 (X) did not answer; check the cable"))));

        await _run.StartCommand.ExecuteAsync(null);

        Assert.Equal(RunState.Failed, _run.State);
        Assert.Contains("did not answer", _run.Error, StringComparison.Ordinal);
        _store.Received(1).Save(Arg.Is<RunRecord>(r => r.Outcome == RunOutcome.Refused));
    }

    [Fact]
    public async Task Abort_WhileRunning_CancelsRunAndRecordsAborted()
    {
        await ReadyAsync();
        var started = new TaskCompletionSource();
        _runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(async c =>
            {
                c.Arg<IProgress<EngraveProgress>>().Report(Report(RunState.Running, 1, 10, 0, 5));
                started.SetResult();
                await Task.Delay(Timeout.Infinite, c.Arg<CancellationToken>()).ContinueWith(_ => { }, TaskScheduler.Default);
                return Ended(c.Arg<EngraveSession>(), Result(RunOutcome.Aborted, "aborted by the operator"));
            });
        var run = _run.StartCommand.ExecuteAsync(null);
        await started.Task.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);
        Assert.Equal(RunState.Running, _run.State);

        _run.AbortCommand.Execute(null);
        await run.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);

        Assert.Equal(RunState.Aborted, _run.State);
        _store.Received(1).Save(Arg.Is<RunRecord>(r => r.Outcome == RunOutcome.Aborted));
    }

    [Fact]
    public async Task PauseResume_WhileRunning_ForwardedToTheSessionAndMirrored()
    {
        await ReadyAsync();
        var started = new TaskCompletionSource<EngraveSession>();
        var finish = new TaskCompletionSource();
        _runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(async c =>
            {
                c.Arg<IProgress<EngraveProgress>>().Report(Report(RunState.Running, 1, 10, 0, 5));
                started.SetResult(c.Arg<EngraveSession>());
                await finish.Task;
                return Ended(c.Arg<EngraveSession>(), Result(RunOutcome.Completed));
            });
        var run = _run.StartCommand.ExecuteAsync(null);
        var session = await started.Task.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);

        _run.PauseCommand.Execute(null);
        var paused = (session.Progress.PauseRequested, _run.CanResume, _run.PauseCommand.CanExecute(null));
        _run.ResumeCommand.Execute(null);
        var resumed = (session.Progress.PauseRequested, _run.CanResume, _run.PauseCommand.CanExecute(null));
        finish.SetResult();
        await run.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);

        Assert.Equal((true, true, false), paused);
        Assert.Equal((false, false, true), resumed);
    }

    [Fact]
    public async Task RemainingSeconds_TwoPassesFirstUnderWay_ExecutorFigurePlusNextPass()
    {
        await ReadyAsync();
        _job.Passes = 2;
        var perPass = _job.Job!.Statistics.EngravingSeconds + _job.Job.Statistics.PassSetupSeconds;
        var reported = new TaskCompletionSource();
        var finish = new TaskCompletionSource();
        _runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(async c =>
            {
                c.Arg<IProgress<EngraveProgress>>().Report(Report(RunState.Running, 5, 10, 2, 4, pass: 1, passes: 2, laserOn: true, remainingSeconds: 30));
                reported.SetResult();
                await finish.Task;
                return Ended(c.Arg<EngraveSession>(), Result(RunOutcome.Completed));
            });
        var run = _run.StartCommand.ExecuteAsync(null);
        await reported.Task.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);

        var remaining = _run.RemainingSeconds;
        var fraction = _run.Fraction;
        finish.SetResult();
        await run.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);

        Assert.Equal(30 + perPass, remaining, 6);
        Assert.Equal(0.25, fraction, 6);
    }

    [Fact]
    public async Task Abort_WhileAContinuedRunRuns_CancelsItAndRecordsAborted()
    {
        await ReadyAsync();
        var continued = new TaskCompletionSource();
        _runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(
                Ends(Result(RunOutcome.Failed, "x axis: no reply") with { StopPoint = new RunStopPoint(3, 20, null, null) }),
                async c =>
                {
                    c.Arg<IProgress<EngraveProgress>>().Report(Report(RunState.Running, 21, 100, 3, 10));
                    continued.SetResult();
                    await Task.Delay(Timeout.Infinite, c.Arg<CancellationToken>()).ContinueWith(_ => { }, TaskScheduler.Default);
                    return Ended(c.Arg<EngraveSession>(), Result(RunOutcome.Aborted, "aborted by the operator"));
                });
        await _run.StartCommand.ExecuteAsync(null);
        var run = _run.ContinueCommand.ExecuteAsync(null);
        await continued.Task.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);

        _run.AbortCommand.Execute(null);
        await run.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);

        Assert.Equal(RunState.Aborted, _run.State);
        _store.Received(1).Save(Arg.Is<RunRecord>(r => r.Outcome == RunOutcome.Aborted && r.Resumed));
    }

    [Fact]
    public void Abort_NothingRunning_Harmless()
    {
        _run.AbortCommand.Execute(null);

        Assert.Equal(RunState.Idle, _run.State);
        Assert.True(_run.AbortCommand.CanExecute(null));
    }

    /// <summary>A run that holds until the test releases it (or it is aborted), so the test acts while it is under way.</summary>
    private async Task<(Task Run, TaskCompletionSource Release, List<CancellationToken> Tokens)> StartHeldRunAsync()
    {
        await ReadyAsync();
        var started = new TaskCompletionSource();
        var release = new TaskCompletionSource();
        var tokens = new List<CancellationToken>();
        _runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(async c =>
            {
                var token = c.Arg<CancellationToken>();
                tokens.Add(token);
                c.Arg<IProgress<EngraveProgress>>().Report(Report(RunState.Running, 1, 10, 0, 5));
                started.TrySetResult();
                await release.Task.WaitAsync(token);
                return Ended(c.Arg<EngraveSession>(), Result(RunOutcome.Completed));
            });
        var run = _run.StartCommand.ExecuteAsync(null);
        await started.Task.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);
        return (run, release, tokens);
    }

    [Fact]
    public async Task Start_SecondStartWhileRunning_IgnoredWithNoteAndRunGoesOn()
    {
        var (run, release, tokens) = await StartHeldRunAsync();

        await _run.StartCommand.ExecuteAsync(null);

        Assert.Equal(RunState.Running, _run.State);
        Assert.False(Assert.Single(tokens).IsCancellationRequested);
        Assert.Contains("already under way", _run.Notice, StringComparison.Ordinal);
        Assert.False(_run.StartCommand.CanExecute(null));
        release.SetResult();
        await run.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);
        Assert.Equal(RunState.Completed, _run.State);
        await _runs.Received(1).RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task MachineCommands_WhileRunning_RefusedSayingARunIsUnderWayAndDisabled()
    {
        var (run, release, _) = await StartHeldRunAsync();
        _fakes.X.ClearReceivedCalls();

        Assert.False(_machine.HomeCommand.CanExecute(null));
        Assert.False(_machine.DisconnectCommand.CanExecute(null));
        Assert.False(_machine.IdentifyCommand.CanExecute(null));
        Assert.False(_machine.ConnectCommand.CanExecute(null));
        await _machine.HomeCommand.ExecuteAsync(null);
        Assert.Contains("a run is under way", _machine.Error, StringComparison.Ordinal);
        await _machine.DisconnectCommand.ExecuteAsync(null);

        Assert.True(_machine.IsConnected);
        await _fakes.X.DidNotReceive().HomeAsync(Arg.Any<CancellationToken>());
        await _fakes.Connection.DidNotReceive().DisposeAsync();
        release.SetResult();
        await run.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);
        Assert.True(_machine.HomeCommand.CanExecute(null));
    }

    [Fact]
    public async Task JobChange_WhileRunning_RefusedSayingARunIsUnderWay()
    {
        var (run, release, _) = await StartHeldRunAsync();
        var width = _job.WidthMm;

        var error = Assert.Throws<MachineBusyException>(() => _job.EditWidth(width * 2));
        Assert.Throws<MachineBusyException>(() => _job.OriginXMm = 7);
        Assert.Throws<MachineBusyException>(() => _job.ThresholdPercent = 10);
        Assert.Throws<MachineBusyException>(() => _job.LoadImage(TestFiles.Asset("text-banner.png")));

        Assert.Contains("a run is under way", error.Message, StringComparison.Ordinal);
        Assert.Equal(width, _job.WidthMm);
        Assert.NotNull(_job.LockedBecause);
        release.SetResult();
        await run.WaitAsync(TimeSpan.FromSeconds(10), TestContext.Current.CancellationToken);
        Assert.Null(_job.LockedBecause);
        _job.OriginXMm = 7;
    }

    [Fact]
    public async Task Start_WhileHoming_RefusedSayingHomingIsUnderWay()
    {
        await ReadyAsync();
        using var homing = _activity.Begin(MachineOperation.Homing);

        Assert.False(_run.StartCommand.CanExecute(null));
        await _run.StartCommand.ExecuteAsync(null);

        Assert.Contains("homing is under way", _run.Error, StringComparison.Ordinal);
        await _runs.DidNotReceive().RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public async Task Continue_JobChangedThenSetBack_OfferedAgainWithTheStoppedPlan()
    {
        await ReadyAsync();
        var stop = new RunStopPoint(3, 20, null, null);
        var sessions = new List<EngraveSession>();
        _runs.RunAsync(Arg.Do<EngraveSession>(sessions.Add), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(Ends(Result(RunOutcome.Failed, "x axis: no reply") with { StopPoint = stop }), Ends(Result(RunOutcome.Completed)));
        await _run.StartCommand.ExecuteAsync(null);
        var origin = _job.OriginXMm;

        _job.OriginXMm = origin + 2;
        Assert.False(_run.CanContinue);
        Assert.False(_run.ContinueCommand.CanExecute(null));
        Assert.Contains("(Origin X)", _run.ContinueUnavailableReason, StringComparison.Ordinal);
        Assert.Equal(stop, _run.StoppedAt);
        _job.OriginXMm = origin;

        Assert.True(_run.CanContinue);
        Assert.Null(_run.ContinueUnavailableReason);
        await _run.ContinueCommand.ExecuteAsync(null);
        Assert.Equal(RunState.Completed, _run.State);
        Assert.Same(sessions[0].Job, sessions[1].Job);
        Assert.Equal(stop, sessions[1].Options.ResumeFrom);
    }
}
