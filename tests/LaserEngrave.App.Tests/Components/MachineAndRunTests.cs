using Bunit;
using LaserEngrave.App.Components.Pages;
using LaserEngrave.App.Components.Workspace;
using LaserEngrave.App.Services;
using LaserEngrave.App.Tests.ViewModels;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Execution;
using NSubstitute;

namespace LaserEngrave.App.Tests.Components;

public sealed class MachinePanelTests : ComponentTest
{
    [Fact]
    public void Connect_Clicked_ConnectedAndConnectDisabled()
    {
        var cut = Render<MachinePanel>(p => p.Add(c => c.Machine, Main.Machine));
        Assert.True(Disabled(cut.Find("#home")));

        cut.Find("#connect").Click();

        // The connection shows as soon as it opens; Home waits until the whole connect command has finished.
        cut.WaitForAssertion(() => Assert.Equal("fake machine", cut.Find("#machine-connection").TextContent));
        cut.WaitForAssertion(() => Assert.False(Disabled(cut.Find("#home"))));
        Assert.True(Disabled(cut.Find("#connect")));
        Assert.Contains("X yes", cut.Find("#machine-homed").TextContent, StringComparison.Ordinal);
    }

    [Fact]
    public void SerialPorts_Chosen_PortFieldsShown()
    {
        var cut = Render<MachinePanel>(p => p.Add(c => c.Machine, Main.Machine));
        Assert.Empty(cut.FindAll("#stagePort"));

        cut.Find("#use-ports").Change(true);

        Assert.False(Main.Machine.UseSimulator);
        Assert.NotNull(cut.Find("#stagePort"));
    }

    [Fact]
    public void ListPorts_NoneFound_SaysSo()
    {
        Machine.Factory.ListPorts().Returns([]);
        var cut = Render<MachinePanel>(p => p.Add(c => c.Machine, Main.Machine));
        cut.Find("#use-ports").Change(true);

        cut.Find("#refresh-ports").Click();

        Assert.StartsWith("No serial ports found on this computer", cut.Find("#ports-note").TextContent, StringComparison.Ordinal);
    }

    [Fact]
    public void Facts_ShowTheProfilesEdgeToleranceInAFewWordsAndAsPreflightSaysItInTheTooltip()
    {
        var cut = Render<MachinePanel>(p => p.Add(c => c.Machine, Main.Machine));

        var fact = cut.Find("#machine-edge-tolerance");
        var tolerance = Main.Machine.Profile.EdgeToleranceUm.ToString(System.Globalization.CultureInfo.InvariantCulture);
        Assert.Equal($"edge tolerance {tolerance} µm", fact.TextContent);
        Assert.StartsWith($"edge tolerance {tolerance} µm: a switch-on this computer sends later than that", fact.GetAttribute("title"), StringComparison.Ordinal);
    }

    [Fact]
    public void NoWatchdogBox_FrequencyOnlyProfile_SaysWhatProtectsTheLaserAndTickingItAccepts()
    {
        Main.Machine.Profile = FrequencyOnlyProfile();
        var cut = Render<MachinePanel>(p => p.Add(c => c.Machine, Main.Machine));
        Assert.NotNull(Main.Machine.NoWatchdogUnaccepted);

        var box = cut.Find("#accept-no-watchdog");
        Assert.Contains(Core.Geometry.LaserGateProfile.NoWatchdogSentence, cut.Find("#no-watchdog").TextContent, StringComparison.Ordinal);
        Assert.False(box.HasAttribute("checked"));
        box.Change(true);

        Assert.True(Main.Machine.AcceptNoWatchdog);
        Assert.Null(Main.Machine.NoWatchdogUnaccepted);
    }

    [Fact]
    public void NoWatchdogBox_DefaultProfile_NotShown()
    {
        var cut = Render<MachinePanel>(p => p.Add(c => c.Machine, Main.Machine));

        Assert.Empty(cut.FindAll("#accept-no-watchdog"));
        Assert.Null(Main.Machine.NoWatchdogUnaccepted);
    }

    private static Core.Geometry.MachineProfile FrequencyOnlyProfile() => Core.Geometry.MachineProfile.Load(TestFiles.Asset(Path.Combine("profiles", "frequency-only.json")));

    [Fact]
    public void ListPorts_TwoFound_Named()
    {
        Machine.Factory.ListPorts().Returns(["COM3", "COM4"]);
        var cut = Render<MachinePanel>(p => p.Add(c => c.Machine, Main.Machine));
        cut.Find("#use-ports").Change(true);

        cut.Find("#refresh-ports").Click();

        Assert.Equal("2 serial ports found: COM3, COM4", cut.Find("#ports-note").TextContent);
        Assert.Equal(2, cut.FindAll("#port-list option").Count);
    }
}

public sealed class LogPanelFolderTests : ComponentTest
{
    [Fact]
    public void LogFolder_PathShownToCopy()
    {
        var cut = Render<LogPanel>(p => p.Add(c => c.Log, Main.Log));

        Assert.Equal("/logs", cut.Find("#log-folder").GetAttribute("value"));
        Assert.True(cut.Find("#log-folder").HasAttribute("readonly"));
        Assert.NotNull(cut.Find("#copy-log-folder"));
    }

    [Fact]
    public void Notes_SeveralLines_KeptAsTyped()
    {
        var cut = Render<LogPanel>(p => p.Add(c => c.Log, Main.Log));

        cut.Find("#notes").Change("línea uno\nlínea dos");

        Assert.Equal("textarea", cut.Find("#notes").TagName, ignoreCase: true);
        Assert.Equal("línea uno\nlínea dos", Main.Log.Notes);
    }

    [Fact]
    public void OpenLogFolder_NoFileManager_SaysSoWithThePath()
    {
        Files.OpenFolder("/logs").Returns(false);
        var cut = Render<LogPanel>(p => p.Add(c => c.Log, Main.Log));

        cut.Find("#open-log-folder").Click();

        Assert.Equal("no file manager can show the log folder here (no desktop session): its path is /logs", cut.Find("#log-error").TextContent);
    }

    [Fact]
    public void OpenLogFolder_Opened_NoError()
    {
        Files.OpenFolder("/logs").Returns(true);
        var cut = Render<LogPanel>(p => p.Add(c => c.Log, Main.Log));

        cut.Find("#open-log-folder").Click();

        Files.Received(1).OpenFolder("/logs");
        Assert.Empty(cut.FindAll("#log-error"));
    }
}

public sealed class RunHistoryTests : ComponentTest
{
    [Fact]
    public void History_OpenedSearchedTicked_ExportLinksOffered()
    {
        var image = TestFiles.Asset("qr-code.bmp");
        var job = PreparedJob.Prepare(new JobSpec { ImagePath = image, Size = Core.Geometry.SizeSpec.Width(3) });
        Store.History().Returns(
        [
            new RunLogEntry("/logs/b.json", RunRecord.ForJob(job, "0", DateTimeOffset.UnixEpoch.AddDays(2)) with { Outcome = RunOutcome.Completed, SampleId = "Si-2" }, null),
            new RunLogEntry("/logs/a.json", RunRecord.ForJob(job, "0", DateTimeOffset.UnixEpoch.AddDays(1)) with { Outcome = RunOutcome.Aborted, SampleId = "Glass-1" }, null),
        ]);
        Main.Log.RefreshCommand.Execute(null);
        var cut = Render<LogPanel>(p => p.Add(c => c.Log, Main.Log));

        cut.Find("#open-history").Click();

        Assert.Equal(2, cut.FindAll("#history-table tbody tr").Count);
        Assert.NotNull(cut.Find("#history-export-hint"));
        cut.Find("#history-search").Input("glass");
        cut.WaitForAssertion(() => Assert.Single(cut.FindAll("#history-table tbody tr")));
        cut.Find(".history-tick").Change(true);
        cut.WaitForAssertion(() => Assert.Equal("api/logs/history?format=csv&decimalMark=comma", cut.Find("#history-csv-comma").GetAttribute("href")));
        Assert.NotNull(cut.Find("#history-json"));
        Assert.Equal("/logs/a.json", Assert.Single(Main.Log.SelectedRows).Path);
        cut.Find("#history-close").Click();
        Assert.Empty(cut.FindAll("#history-overlay"));
    }

    [Fact]
    public void History_RunWithLateSwitchesAndRecoveries_SaysThemUnderItsOutcomeOthersNot()
    {
        var image = TestFiles.Asset("qr-code.bmp");
        var job = PreparedJob.Prepare(new JobSpec { ImagePath = image, Size = Core.Geometry.SizeSpec.Width(3) });
        var record = RunRecord.ForJob(job, "0", DateTimeOffset.UnixEpoch) with { Outcome = RunOutcome.Completed };
        Store.History().Returns(
        [
            new RunLogEntry("/logs/late.json", record with { LateSwitches = new LateSwitches(4, 1.42, 1.5), Recoveries = [new RunRecovery(1, "late", 40, 12), new RunRecovery(1, "late", 90, 20)] }, null),
            new RunLogEntry("/logs/clean.json", record, null),
        ]);
        Main.Log.RefreshCommand.Execute(null);
        var cut = Render<RunHistoryDialog>(p => p.Add(c => c.Log, Main.Log));

        Assert.Equal(
            "late switch-ons: 4 within the 1.5 µm edge tolerance (latest 1.42 µm); went on after 2 timing doubts",
            cut.Find("tr[data-path='/logs/late.json'] .history-timing").TextContent);
        Assert.Empty(cut.FindAll("tr[data-path='/logs/clean.json'] .history-timing"));
    }
}

public sealed class JogPadTests : ComponentTest
{
    [Fact]
    public async Task Jog_NotConnected_Disabled_Connected_Moves()
    {
        var cut = Render<JogPad>(p => p.Add(c => c.Moves, Main.TestMoves).Add(c => c.Machine, Main.Machine));
        Assert.True(Disabled(cut.Find("[id='jog-x+']")));

        await ConnectAsync();
        cut.WaitForAssertion(() => Assert.False(Disabled(cut.Find("[id='jog-x+']"))));
        cut.Find("[id='jog-x+']").Click();

        cut.WaitForAssertion(() => Assert.StartsWith("X 0.100", cut.Find("#position").TextContent, StringComparison.Ordinal));
    }

    [Fact]
    public async Task GoTo_Running_BusyWithStop_StopCancelsIt()
    {
        await ConnectAsync();
        Machine.X.MoveAbsoluteAsync(Arg.Any<long>(), Arg.Any<CancellationToken>())
            .Returns(async c =>
            {
                // A move that ends only by its cancellation, as the stage's does when Stop cancels it.
                await Task.Delay(Timeout.Infinite, c.Arg<CancellationToken>());
                return 0L;
            });
        var cut = Render<JogPad>(p => p.Add(c => c.Moves, Main.TestMoves).Add(c => c.Machine, Main.Machine));
        cut.Find("#goto-x").Change("12");

        cut.Find("#goto").Click();

        cut.WaitForAssertion(() => Assert.Contains("Going to 12, 0 mm", cut.Find("#moves-busy").TextContent, StringComparison.Ordinal));
        Assert.True(Disabled(cut.Find("[id='jog-x+']")));
        cut.Find("#moves-stop").Click();
        cut.WaitForAssertion(() => Assert.Empty(cut.FindAll("#moves-busy")));

        // The line goes when the machine is free; the move's outcome is taken just after.
        cut.WaitForAssertion(() => Assert.Equal("cancelled", Main.TestMoves.Error));
    }

    [Fact]
    public async Task Frame_NoJob_Disabled()
    {
        await ConnectAsync();

        var cut = Render<JogPad>(p => p.Add(c => c.Moves, Main.TestMoves).Add(c => c.Machine, Main.Machine));

        Assert.True(Disabled(cut.Find("#frame")));
        Assert.Equal("Frame: open an image or drawing first", cut.Find("#frame").GetAttribute("title"));
        Assert.False(Disabled(cut.Find("#goto")));
    }

    [Fact]
    public async Task Frame_Drawing_Enabled()
    {
        await ConnectAsync();
        Main.Job.LoadImage(TestFiles.Asset(Path.Combine("drawings", "hexagons.dxf")));

        var cut = Render<JogPad>(p => p.Add(c => c.Moves, Main.TestMoves).Add(c => c.Machine, Main.Machine));

        Assert.False(Disabled(cut.Find("#frame")));
        Assert.False(Disabled(cut.Find("#goto-origin")));
    }
}

public sealed class RunBarTests : ComponentTest
{
    private IRenderedComponent<RunBar> RenderBar() => Render<RunBar>(p => p.Add(c => c.Run, Main.Run));

    [Fact]
    public async Task Start_EnabledOnlyWithAJobAndAMachine()
    {
        var cut = RenderBar();
        Assert.True(Disabled(cut.Find("#start")));
        OpenQr();
        Assert.True(Disabled(cut.Find("#start")));

        await ConnectAsync();

        cut.WaitForAssertion(() => Assert.False(Disabled(cut.Find("#start"))));
        Assert.True(Disabled(cut.Find("#pause")));
        Assert.True(Disabled(cut.Find("#continue")));
        Assert.True(Disabled(cut.Find("#abort")));
    }

    // The QR at a 5 µm pitch, connected, Start pressed: slow enough that a 5 µm pixel lasts the gate's switching time (a
    // job the rules take), so only its pixels, much smaller than the spot, make Start ask.
    private async Task<IRenderedComponent<RunBar>> StartSmallPixelJobAsync()
    {
        OpenQr();
        Main.Job.EditPitch(5);
        Main.Job.BurnSpeedMmPerS = 0.25;
        await ConnectAsync();
        var cut = RenderBar();
        cut.WaitForAssertion(() => Assert.False(Disabled(cut.Find("#start"))));
        cut.Find("#start").Click();
        return cut;
    }

    [Fact]
    public async Task Start_PixelsMuchSmallerThanTheSpot_AsksOnceWithTheNumbers()
    {
        var cut = await StartSmallPixelJobAsync();

        cut.WaitForAssertion(() => Assert.Contains("Its pixels of 5 µm are much smaller than the 20 µm laser spot, so each burns about 4 times wider", cut.Find("#start-question").TextContent, StringComparison.Ordinal));
        await Runs.DidNotReceive().RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>());
        cut.Find("#start-cancel").Click();
        // The question goes with the next render of the bar, not within the click.
        cut.WaitForAssertion(() => Assert.Empty(cut.FindAll("#start-question")));
        cut.Find("#start").Click();
        cut.WaitForAssertion(() => Assert.NotNull(cut.Find("#start-confirm")));
        cut.Find("#start-confirm").Click();
        cut.WaitForAssertion(() => Runs.Received(1).RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>()));
        cut.WaitForAssertion(() => Assert.Empty(cut.FindAll("#start-question")));
    }

    [Fact]
    public async Task StartAnyway_JobChangedWhileAsking_AsksAgainOrRefusesNeverStartsTheNewJobUnasked()
    {
        var cut = await StartSmallPixelJobAsync();
        cut.WaitForAssertion(() => Assert.Contains("pixels of 5 µm", cut.Find("#start-question").TextContent, StringComparison.Ordinal));

        Main.Job.EditPitch(4);
        cut.Find("#start-confirm").Click();

        cut.WaitForAssertion(() => Assert.Contains("pixels of 4 µm", cut.Find("#start-question").TextContent, StringComparison.Ordinal));
        Assert.Contains("the job changed while Start was asking", cut.Find("#run-notice").TextContent, StringComparison.Ordinal);
        await Runs.DidNotReceive().RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>());

        Main.Job.EditPitch(20);
        Main.Job.BurnSpeedMmPerS = 1;
        cut.Find("#start-confirm").Click();

        cut.WaitForAssertion(() => Assert.Empty(cut.FindAll("#start-question")));
        Assert.Contains("nothing started; press Start", cut.Find("#run-notice").TextContent, StringComparison.Ordinal);
        await Runs.DidNotReceive().RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>());
    }

    [Fact]
    public void StartQuestion_OverAnHour_SaysHowLong()
    {
        OpenQr(widthMm: 20);
        Assert.Null(Main.Run.StartQuestion);

        Main.Job.Passes = 100;

        Assert.True(Main.Job.EstimatedSeconds > RunViewModel.DefaultAskAboveMinutes * 60, $"{Main.Job.EstimatedSeconds} s");
        Assert.StartsWith($"Start anyway? It takes about {App.Components.Format.Duration(Main.Job.EstimatedSeconds!.Value)}", Main.Run.StartQuestion, StringComparison.Ordinal);
    }

    [Fact]
    public void StartQuestion_ThresholdSetBelowTheEstimate_AsksForARunUnderAnHourAndKeepsTheSetting()
    {
        OpenQr(widthMm: 20);
        var estimate = Main.Job.EstimatedSeconds!.Value;
        Assert.True(estimate < 3600, $"{estimate} s");
        Assert.Null(Main.Run.StartQuestion);
        var panel = Render<MachinePanel>(p => p.Add(c => c.Machine, Main.Machine));
        var minutes = Math.Round(estimate / 60 / 2, 2);

        panel.Find("#ask-above-minutes").Change(minutes.ToString(System.Globalization.CultureInfo.InvariantCulture).Replace('.', ','));

        Assert.Equal(minutes, Main.Run.AskAboveMinutes);
        Assert.StartsWith("Start anyway? It takes about", Main.Run.StartQuestion, StringComparison.Ordinal);
        Settings.Received().Save(Arg.Is<AppSettings>(s => s.AskAboveMinutes == minutes));
    }

    [Fact]
    public void AskAboveMinutes_Negative_RefusedWithTheRangeAndKeepsTheHour()
    {
        var panel = Render<MachinePanel>(p => p.Add(c => c.Machine, Main.Machine));

        panel.Find("#ask-above-minutes").Change("-5");

        Assert.Equal(RunViewModel.DefaultAskAboveMinutes, Main.Run.AskAboveMinutes);
        panel.WaitForAssertion(() => Assert.Contains("give 0 (ask before every run) to 10080 min", panel.Find("[data-error='ask-above-minutes']").TextContent, StringComparison.Ordinal));
    }

    [Fact]
    public void AskAboveMinutes_SavedSetting_UsedAtTheNextStart()
    {
        var settings = Substitute.For<ISettingsStore>();
        settings.Load().Returns(new AppSettings { AskAboveMinutes = 30 });

        var main = new MainViewModel(new ImageService(), Machine.Factory, Runs, Store, settings, Files, TimeProvider.System, new MachineActivity(), new JobFiles(new AppFolders(DataFolder.Path)));

        Assert.Equal(30, main.Run.AskAboveMinutes);
    }

    [Fact]
    public async Task TestMove_UnderWay_RunBarSaysWhatAndStopsIt()
    {
        await ConnectAsync();
        var cut = Render<RunBar>(p => p.Add(c => c.Run, Main.Run).Add(c => c.Moves, Main.TestMoves).Add(c => c.Sweep, Main.Sweep));
        Assert.Empty(cut.FindAll("#runbar-stop"));

        using (var lease = Main.Machine.Activity.Begin(MachineOperation.TestMove("frame", "Tracing the job's frame, laser off…")))
        {
            cut.WaitForAssertion(() => Assert.Contains("Tracing the job's frame, laser off…", cut.Find("#status-run").TextContent, StringComparison.Ordinal));
            cut.Find("#runbar-stop").Click();
            Assert.True(lease.CancellationToken.IsCancellationRequested);
        }

        cut.WaitForAssertion(() => Assert.Equal("idle", cut.Find("#status-run").TextContent));
        Assert.Empty(cut.FindAll("#runbar-stop"));
    }

    [Fact]
    public async Task Run_SecondOfTenOnePassLayers_PassCountedWithinTheLayer()
    {
        OpenQr();
        await ConnectAsync();
        var release = new TaskCompletionSource<RunResult>();
        Runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>()).Returns(async c =>
        {
            // The session's pass 2 of the 10 summed over ten one-pass layers is the second layer's only pass.
            c.Arg<IProgress<EngraveProgress>>().Report(SessionResults.Report(RunState.Running, 50, 100, 10, 20, pass: 2, passes: 10) with { Layer = 2, LayerPass = 1, LayerPasses = 1 });
            return SessionResults.Ended(c.Arg<EngraveSession>(), await release.Task);
        });
        var cut = RenderBar();

        cut.Find("#start").Click();

        cut.WaitForAssertion(() => Assert.Equal("row 10 of 20", cut.Find("#progress-figures").TextContent));
        release.SetResult(SessionResults.Result(RunOutcome.Completed));
    }

    [Fact]
    public async Task Run_UnderWay_ProgressPauseResume()
    {
        OpenQr();
        await ConnectAsync();
        var release = new TaskCompletionSource<RunResult>();
        Runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>()).Returns(async c =>
        {
            var progress = c.Arg<IProgress<EngraveProgress>>();
            var session = c.Arg<EngraveSession>();
            progress.Report(SessionResults.Report(RunState.Running, 50, 100, 10, 20, laserOn: true));
            return SessionResults.Ended(session, await release.Task);
        });
        var cut = RenderBar();

        cut.Find("#start").Click();

        cut.WaitForAssertion(() => Assert.Equal("50 %", cut.Find("#progress-text").TextContent));
        Assert.Contains("row 10 of 20", cut.Find("#progress-figures").TextContent, StringComparison.Ordinal);
        Assert.True(Disabled(cut.Find("#start")));
        Assert.False(Disabled(cut.Find("#abort")));
        cut.Find("#pause").Click();
        cut.WaitForAssertion(() => Assert.Empty(cut.FindAll("#pause")));
        cut.Find("#resume").Click();
        cut.WaitForAssertion(() => Assert.Empty(cut.FindAll("#resume")));
        Assert.Equal("running", cut.Find("#status-run").TextContent);
        cut.Find("#abort").Click();
        release.SetResult(new RunResult
        {
            Outcome = RunOutcome.Aborted, LaserOffConfirmed = true, StartedAt = DateTimeOffset.UnixEpoch, EndedAt = DateTimeOffset.UnixEpoch,
            EngravingDuration = TimeSpan.Zero, EstimatedSeconds = 1, LaserOnSeconds = 0, RowsDone = 10, RowsTotal = 20, RunsDone = 3, RunsTotal = 7,
        });
        cut.WaitForAssertion(() => Assert.Equal("aborted", cut.Find("#status-run").TextContent));
    }

    [Fact]
    public async Task Run_LaserOnInTheEngine_PanelAndStateSayFiringAsTheRunDoes()
    {
        // Issue 31, finding 2: during a run the panel and /api/state said "off" (the gate read before the run) while run.laserOn was true.
        OpenQr();
        await ConnectAsync();
        Assert.Equal("off", Main.Machine.GateState);
        var release = new TaskCompletionSource<RunResult>();
        var firing = new TaskCompletionSource<IProgress<EngraveProgress>>();
        Runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>()).Returns(async c =>
        {
            var progress = c.Arg<IProgress<EngraveProgress>>();
            progress.Report(SessionResults.Report(RunState.Running, 50, 100, 10, 20, laserOn: true));
            firing.SetResult(progress);
            return SessionResults.Ended(c.Arg<EngraveSession>(), await release.Task);
        });
        var panel = Render<MachinePanel>(p => p.Add(c => c.Machine, Main.Machine));
        var hz = (int)Main.Job.LaserFrequencyHz;

        var run = Main.Run.StartCommand.ExecuteAsync(null);
        var progress = await firing.Task;

        panel.WaitForAssertion(() => Assert.Equal($"firing at {hz} Hz", panel.Find("#machine-gate").TextContent));
        var state = System.Text.Json.JsonSerializer.SerializeToElement(global::LaserEngrave.App.Web.StateSnapshot.From(Main));
        Assert.Equal($"firing at {hz} Hz", state.GetProperty("machine").GetProperty("gateState").GetString());
        Assert.True(state.GetProperty("run").GetProperty("laserOn").GetBoolean());

        progress.Report(SessionResults.Report(RunState.Running, 51, 100, 10, 20, laserOn: false));
        panel.WaitForAssertion(() => Assert.Equal("off", panel.Find("#machine-gate").TextContent));
        state = System.Text.Json.JsonSerializer.SerializeToElement(global::LaserEngrave.App.Web.StateSnapshot.From(Main));
        Assert.Equal("off", state.GetProperty("machine").GetProperty("gateState").GetString());
        Assert.False(state.GetProperty("run").GetProperty("laserOn").GetBoolean());

        release.SetResult(new RunResult
        {
            Outcome = RunOutcome.Completed, LaserOffConfirmed = true, StartedAt = DateTimeOffset.UnixEpoch, EndedAt = DateTimeOffset.UnixEpoch,
            EngravingDuration = TimeSpan.Zero, EstimatedSeconds = 1, LaserOnSeconds = 0, RowsDone = 20, RowsTotal = 20, RunsDone = 7, RunsTotal = 7,
        });
        await run;
        Assert.Equal("off", Main.Machine.GateState);
    }

    [Fact]
    public async Task Run_FailsOnAStageThatStoppedAnswering_PanelNoLongerSaysHomedAndTheCrossStaysWhereTheRunStopped()
    {
        // Issue 31, finding 8: after a stage went silent the panel still said homed and the cross was drawn at 0, 0.
        OpenQr();
        await ConnectAsync();
        Assert.Contains("X yes", Render<MachinePanel>(p => p.Add(c => c.Machine, Main.Machine)).Find("#machine-homed").TextContent, StringComparison.Ordinal);
        Runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>()).Returns(c =>
        {
            c.Arg<IProgress<EngraveProgress>>().Report(SessionResults.Report(RunState.Running, 30, 100, 8, 33, x: 19484, y: 6760));
            Machine.Y.IdentifyAsync(Arg.Any<CancellationToken>()).Returns<AxisIdentity>(_ => throw new DeviceException("the Y axis (device 2) does not answer"));
            return Task.FromResult(SessionResults.Ended(c.Arg<EngraveSession>(), new RunResult
            {
                Outcome = RunOutcome.Failed, FaultMessage = "the Y axis (device 2) does not answer", LaserOffConfirmed = true, StartedAt = DateTimeOffset.UnixEpoch, EndedAt = DateTimeOffset.UnixEpoch,
                EngravingDuration = TimeSpan.Zero, EstimatedSeconds = 1, LaserOnSeconds = 0, RowsDone = 8, RowsTotal = 33, RunsDone = 60, RunsTotal = 284,
                StopPoint = new RunStopPoint(12, 30, 19484, 6760),
            }));
        });

        await Main.Run.StartCommand.ExecuteAsync(null);

        var panel = Render<MachinePanel>(p => p.Add(c => c.Machine, Main.Machine));
        Assert.Equal("X ?, Y ?", panel.Find("#machine-homed").TextContent);
        Assert.Equal("the Y axis (device 2) does not answer", Main.Machine.Error);
        Assert.Equal((19484L, 6760L), (Main.Machine.XMicrosteps, Main.Machine.YMicrosteps));
        var bar = RenderBar();
        Assert.Contains("row 8 of 33", bar.Find("#progress-figures").TextContent, StringComparison.Ordinal);
        Assert.Equal("stopped after 8 of 33 rows, stage at X 1.933 mm, Y 0.671 mm (19484, 6760 microsteps)", bar.Find("#stopped-at").TextContent);
    }

    [Fact]
    public async Task Run_OfADrawing_CountsStrokesAsTheCommandLineAndTheLogDo()
    {
        Assert.True(Main.Job.LoadImage(TestFiles.Asset(Path.Combine("drawings", "hexagons.dxf"))));
        await ConnectAsync();
        var release = new TaskCompletionSource<RunResult>();
        Runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>()).Returns(async c =>
        {
            c.Arg<IProgress<EngraveProgress>>().Report(SessionResults.Report(RunState.Running, 50, 100, 20, 39));
            return SessionResults.Ended(c.Arg<EngraveSession>(), await release.Task);
        });
        var cut = RenderBar();

        cut.Find("#start").Click();

        cut.WaitForAssertion(() => Assert.StartsWith("stroke 20 of 39", cut.Find("#progress-figures").TextContent, StringComparison.Ordinal));
        release.SetResult(new RunResult
        {
            Outcome = RunOutcome.Completed, LaserOffConfirmed = true, StartedAt = DateTimeOffset.UnixEpoch, EndedAt = DateTimeOffset.UnixEpoch,
            EngravingDuration = TimeSpan.Zero, EstimatedSeconds = 1, LaserOnSeconds = 0, RowsDone = 39, RowsTotal = 39, RunsDone = 9, RunsTotal = 9,
        });
        cut.WaitForAssertion(() => Assert.Equal("completed", cut.Find("#status-run").TextContent));
        var log = Render<LogPanel>(p => p.Add(c => c.Log, Main.Log));
        Assert.Contains("strokes 39 of 39", log.Find("#last-run").TextContent, StringComparison.Ordinal);
    }

    [Fact]
    public async Task NewJob_AfterARun_StaleProgressCleared()
    {
        OpenQr();
        await ConnectAsync();
        Runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>()).Returns(c =>
        {
            c.Arg<IProgress<EngraveProgress>>().Report(SessionResults.Report(RunState.Running, 100, 100, 33, 33));
            return Task.FromResult(SessionResults.Ended(c.Arg<EngraveSession>(), new RunResult
            {
                Outcome = RunOutcome.Completed, LaserOffConfirmed = true, StartedAt = DateTimeOffset.UnixEpoch, EndedAt = DateTimeOffset.UnixEpoch,
                EngravingDuration = TimeSpan.Zero, EstimatedSeconds = 1, LaserOnSeconds = 0, RowsDone = 33, RowsTotal = 33, RunsTotal = 7, RunsDone = 7,
            }));
        });
        await Main.Run.StartCommand.ExecuteAsync(null);
        var cut = RenderBar();
        Assert.Equal("100 %", cut.Find("#progress-text").TextContent);

        Main.Job.EditWidth(8);

        cut.WaitForAssertion(() => Assert.Equal("0 %", cut.Find("#progress-text").TextContent));
        Assert.Empty(cut.FindAll("#progress-figures"));
        Assert.Equal("idle", cut.Find("#status-run").TextContent);
    }

    // The session's own word that a preflight is a recovery's (EngraveProgress.Recovering), not a new start's.
    [Theory]
    [InlineData(RunState.Preflight, false, "starting: checking the machine")]
    [InlineData(RunState.Preflight, true, "recovering: checking the machine again")]
    [InlineData(RunState.Running, false, "running")]
    public void RunBar_StateText_SaysARecoveryAsSuch(RunState state, bool recovering, string expected) =>
        Assert.Equal(expected, RunBar.StateText(state, recovering));
}

public sealed class LogPanelTests : ComponentTest
{
    [Fact]
    public void RunRecorded_SummaryAndExportLinks()
    {
        OpenQr();
        var record = RunRecord.ForJob(Main.Job.Job!, "hash", DateTimeOffset.UnixEpoch) with { SampleId = "B-7" };
        var cut = Render<LogPanel>(p => p.Add(c => c.Log, Main.Log));

        Main.Log.Record(record with { EndedAt = DateTimeOffset.UnixEpoch, Outcome = RunOutcome.Completed });

        cut.WaitForAssertion(() => Assert.Contains("B-7", cut.Find("#last-run").TextContent, StringComparison.Ordinal));
        Assert.Contains("format=json", cut.Find("#export-json").GetAttribute("href"), StringComparison.Ordinal);
        Assert.Contains(Uri.EscapeDataString("/logs/run.json"), cut.Find("#export-txt").GetAttribute("href"), StringComparison.Ordinal);
        Assert.Empty(cut.FindAll("#last-run-timing"));
    }

    [Fact]
    public void RunRecorded_LateSwitches_TheLastRunLineCountsThem()
    {
        OpenQr();
        var record = RunRecord.ForJob(Main.Job.Job!, "hash", DateTimeOffset.UnixEpoch) with
        {
            Outcome = RunOutcome.Completed,
            LateSwitches = new LateSwitches(4, 1.4213, 1.5),
            Recoveries = [new RunRecovery(1, "switch-on later than the edge tolerance", 40, 12)],
        };
        var cut = Render<LogPanel>(p => p.Add(c => c.Log, Main.Log));

        Main.Log.Record(record);

        cut.WaitForAssertion(() => Assert.Equal(
            "late switch-ons: 4 within the 1.5 µm edge tolerance (latest 1.42 µm); went on after 1 timing doubt",
            cut.Find("#last-run #last-run-timing").TextContent));
    }

    [Fact]
    public async Task HistoryContinue_StoppedRun_ContinuedFromItsLogsStopPointOthersSayWhyNot()
    {
        OpenQr();
        var image = TestFiles.Asset("qr-code.bmp");
        var logged = RunRecord.ForJob(Main.Job.Job!, PreparedJob.HashFile(image), DateTimeOffset.UnixEpoch);
        var stop = new RunStopPoint(3, 10, null, null);
        Store.History().Returns(
        [
            new RunLogEntry("/logs/a.json", logged with { Outcome = RunOutcome.Aborted, StoppedAt = stop, SampleId = "A-1" }, null),
            new RunLogEntry("/logs/b.json", logged with { Outcome = RunOutcome.Failed }, null),
            new RunLogEntry("/logs/c.json", logged with { Outcome = RunOutcome.Completed }, null),
            new RunLogEntry("/logs/d.json", logged with { Outcome = RunOutcome.Aborted, StoppedAt = stop }, null),
            new RunLogEntry("/logs/e.json", logged with { Outcome = RunOutcome.Completed, Resumed = true, RepeatOf = "/logs/d.json" }, null),
        ]);
        Main.Log.RefreshCommand.Execute(null);
        Main.Job.EditWidth(8);
        await ConnectAsync();
        EngraveSession? ran = null;
        Runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(c => SessionResults.Ends(SessionResults.Result(RunOutcome.Completed))(c))
            .AndDoes(c => ran = c.Arg<EngraveSession>());
        var cut = Render<RunHistoryDialog>(p => p.Add(c => c.Log, Main.Log).Add(c => c.Run, Main.Run));

        Assert.Empty(cut.FindAll("tr[data-path='/logs/c.json'] .history-continue"));
        var failed = cut.Find("tr[data-path='/logs/b.json'] .history-continue");
        Assert.True(Disabled(failed));
        Assert.Contains("no stop point", failed.GetAttribute("title"), StringComparison.Ordinal);
        Assert.Contains("continued already (e.json, completed)", cut.Find("tr[data-path='/logs/d.json'] .history-continue").GetAttribute("title"), StringComparison.Ordinal);
        var aborted = cut.Find("tr[data-path='/logs/a.json'] .history-continue");
        Assert.False(Disabled(aborted));
        aborted.Click();

        cut.WaitForAssertion(() => Assert.NotNull(ran));
        Assert.Equal(stop, ran!.Options.ResumeFrom);
        Assert.Equal("/logs/a.json", ran.Options.RepeatOf);
        Assert.Equal(5, Main.Job.WidthMm, 6);
        Assert.Equal("A-1", ran.Options.SampleId);
        Assert.Null(Main.Run.Error);
    }

    [Fact]
    public void SampleId_Typed_KeptForTheNextRun()
    {
        var cut = Render<LogPanel>(p => p.Add(c => c.Log, Main.Log));

        cut.Find("#sampleId").Change("W-12");

        Assert.Equal("W-12", Main.Log.SampleId);
    }
}

public sealed class StageCanvasTests : ComponentTest
{
    private IRenderedComponent<StageCanvas> RenderStage() =>
        Render<StageCanvas>(p => p.Add(c => c.Job, Main.Job).Add(c => c.Machine, Main.Machine).Add(c => c.Moves, Main.TestMoves).Add(c => c.Run, Main.Run));

    [Fact]
    public async Task JobDropped_OnTheStage_OriginSnappedTo10Um()
    {
        OpenQr();
        var cut = RenderStage();

        var accepted = await cut.InvokeAsync(() => cut.Instance.OnJobDropped(20.123, 7.456));

        Assert.True(accepted);
        Assert.Equal((20.12, 7.46), (Main.Job.OriginXMm, Main.Job.OriginYMm));
        Assert.Empty(cut.FindAll("#drop-refused"));
    }

    [Fact]
    public async Task JobDropped_OffTheTravel_RefusedOriginKept()
    {
        OpenQr(widthMm: 10);
        var cut = RenderStage();

        var accepted = await cut.InvokeAsync(() => cut.Instance.OnJobDropped(55, 1));

        Assert.False(accepted);
        Assert.Equal(1, Main.Job.OriginXMm);
        // The typed origin's sentence (issue 35: the drop once had a rule of its own).
        Assert.StartsWith("not placed at 55, 1 mm: the job (10 x ", cut.Find("#drop-refused").TextContent, StringComparison.Ordinal);
        Assert.Contains("does not fit the stage's travel (60 x 60 mm): move the origin or make it smaller", cut.Find("#drop-refused").TextContent, StringComparison.Ordinal);
    }

    [Fact]
    public async Task DropRefused_ThenResized_TheLineGoesWithItsCause()
    {
        OpenQr(widthMm: 10);
        var cut = RenderStage();
        await cut.InvokeAsync(() => cut.Instance.OnJobDropped(55, 1));
        Assert.NotEmpty(cut.FindAll("#drop-refused"));

        Main.Job.EditWidth(4);

        cut.WaitForAssertion(() => Assert.Empty(cut.FindAll("#drop-refused")));
    }

    [Fact]
    public void MicrostepsPerPixel_SizeLeads_ThePlannedJobsOwnFigure()
    {
        OpenQr(widthMm: 10);

        // The figure the command line and the run log give, not one from the pitch field's rounded value.
        Assert.Equal(Main.Job.Job!.Geometry.MicrostepsPerPixel, Main.Job.MicrostepsPerPixel);
    }

    [Fact]
    public async Task MoveLaserHere_Connected_GoesThere()
    {
        await ConnectAsync();
        var cut = RenderStage();

        await cut.InvokeAsync(() => cut.Instance.OnMoveLaserHere(12.346, 30));

        cut.WaitForAssertion(() => Assert.Equal((long)Math.Round(12.35 * 1000 / Profile.X.MicrostepUm), Main.Machine.XMicrosteps), TimeSpan.FromSeconds(10));
        Assert.Null(Main.TestMoves.Error);
        Assert.Equal(12.35, Main.TestMoves.GoToXMm);
    }

    [Fact]
    public void SweepBoxes_PlannedSweep_TheLabelsAndEveryCellPlacedAndNamedByItsValues()
    {
        Main.Job.OriginXMm = 5;
        Main.Job.OriginYMm = 6;
        Main.Sweep.Rows = "speed=0.5,2";
        Main.Sweep.Columns = "frequency=500,1000";
        Main.Sweep.Labels = true;
        var plan = Assert.IsType<LaserEngrave.Core.Sweeps.SweepPlan>(Main.Sweep.Plan);

        var picture = new LaserEngrave.Core.Preview.StagePicture(LaserEngrave.Core.Sweeps.SweepJob.Of(plan));
        var boxes = picture.Boxes;

        Assert.Equal(5, boxes.Count);
        Assert.Equal("labels", boxes[0].Name);
        Assert.Equal(["0.5 mm/s · 1000 Hz", "0.5 mm/s · 500 Hz", "2 mm/s · 1000 Hz", "2 mm/s · 500 Hz"], boxes.Skip(1).Select(b => b.Name).Order(StringComparer.Ordinal));
        foreach (var (box, cell) in boxes.Skip(1).Zip(plan.Cells))
        {
            // Each box is its cell's burn: from the cell's origin, the cell's size, within a pixel.
            var pitch = cell.Job.Geometry.PitchUm / 1000;
            Assert.InRange(box.X - cell.OriginXMm, -pitch, pitch);
            Assert.InRange(box.Y - cell.OriginYMm, -pitch, pitch);
            Assert.InRange(Math.Max(box.W, box.H), plan.Spec.CellMm - pitch, plan.Spec.CellMm + pitch);
            Assert.True(box.Fits);
        }

        var (bytes, drawn, total) = (picture.Moves, picture.Drawn, picture.Total);
        Assert.Equal(plan.Jobs().Sum(j => j.Statistics.Moves), total);
        Assert.Equal(total, drawn);
        Assert.Equal(drawn * 5 * sizeof(float), bytes.Length);
    }

    [Fact]
    public void SweepPanel_ShowOnStage_TheCheckboxSetsIt()
    {
        var cut = Render<SweepPanel>(p => p.Add(c => c.Sweep, Main.Sweep));

        cut.Find("#sweepShow").Change(true);

        Assert.True(Main.Sweep.ShowOnStage);
        Assert.True(Main.Sweep.ShowsOnStage);
    }

    [Fact]
    public void PlanBytes_PlanOfMoreMovesThanDrawn_CappedAndCounted()
    {
        // One-pixel checks: every other pixel a burn run of its own, far more moves than the page draws.
        using var folder = TestFiles.NewFolder();
        var path = TestFiles.WriteChecker(folder.Path, 500, 500, cell: 1);
        Assert.True(Main.Job.LoadImage(path));
        Main.Job.EditWidth(50);

        var (bytes, drawn, total) = LaserEngrave.Core.Preview.StagePicture.PlanMoves(Main.Job.Job);

        Assert.True(total > StageCanvas.MaxDrawnMoves, $"only {total} moves");
        Assert.Equal(StageCanvas.MaxDrawnMoves, drawn);
        Assert.Equal(drawn * 5 * sizeof(float), bytes.Length);
    }

    [Fact]
    public void PlanBytes_DotJob_AllDrawnNoneMissing()
    {
        OpenQr();
        Main.Job.Mode = LaserEngrave.Core.Planning.PlanMode.Dots;
        var job = Assert.IsType<PreparedJob>(Main.Job.Job);

        var (bytes, drawn, total) = LaserEngrave.Core.Preview.StagePicture.PlanMoves(job);

        // Its statistics count the dots as moves too; the page draws every move the plan has, so nothing is "partly drawn".
        Assert.Equal(job.Plan.Moves().Count(), drawn);
        Assert.Equal(drawn, total);
        Assert.Equal(drawn * 5 * sizeof(float), bytes.Length);
    }

    [Fact]
    public void PlanBytes_SmallPlan_AllDrawn()
    {
        OpenQr();

        var (bytes, drawn, total) = LaserEngrave.Core.Preview.StagePicture.PlanMoves(Main.Job.Job);

        Assert.Equal(Main.Job.Job!.Statistics.Moves, total);
        Assert.Equal(total, drawn);
        Assert.Equal(drawn * 5 * sizeof(float), bytes.Length);
        Assert.True(StageCanvas.MaxDrawnMoves <= 100_000);
    }
}

public sealed class WorkspaceTests : ComponentTest
{
    [Fact]
    public void Page_AllPanelsTheStageAndTheRunBar()
    {
        var cut = Render<Workspace>();

        foreach (var id in new[] { "panel-image", "panel-size", "panel-process", "panel-machine", "panel-jog", "panel-log", "stage", "runbar" })
        {
            Assert.NotNull(cut.Find("#" + id));
        }

        Assert.Equal("no image", cut.Find("#status-estimate").TextContent);
        Assert.NotNull(cut.Find("#scan-offset-pattern"));
        Assert.Empty(cut.FindAll("#pattern-error"));
    }

    [Fact]
    public async Task Header_FollowsTheJobAndTheMachine()
    {
        var cut = Render<Workspace>();

        OpenQr(widthMm: 4);
        await ConnectAsync();

        cut.WaitForAssertion(() => Assert.StartsWith("4 × 4 mm", cut.Find("#status-estimate").TextContent, StringComparison.Ordinal));
        cut.WaitForAssertion(() => Assert.Equal("fake machine", cut.Find("#status-machine").TextContent));
    }
}
