using System.Globalization;
using LaserEngrave.App.ViewModels;
using LaserEngrave.App.Web;
using LaserEngrave.Devices.Execution;
using Microsoft.AspNetCore.Builder;
using Microsoft.AspNetCore.Hosting;
using Microsoft.AspNetCore.Http;
using Microsoft.AspNetCore.Hosting.Server;
using Microsoft.AspNetCore.Hosting.Server.Features;
using Microsoft.Extensions.DependencyInjection;
using OpenQA.Selenium;
using OpenQA.Selenium.Chrome;
using OpenQA.Selenium.Interactions;
using OpenQA.Selenium.Support.UI;

namespace LaserEngrave.App.Tests.Web;

/// <summary>The workspace as a user works in it: a first job, drawings, layers, sweeps, undo, the token, the window.</summary>
/// <remarks>Split from <see cref="BrowserLayoutTests"/> so that the two halves run side by side.</remarks>
public sealed class BrowserTests : BrowserTest
{
    [Fact]
    public void JobFile_SingleImageDownloadedThenChosenInTheFileInput_OpensBackAsTheSameJob()
    {
        OpenSample("qr-code.bmp");
        SetField("widthMm", "6");
        WaitFor(d => d.FindElement(By.Id("status-estimate")).Text.StartsWith("6 × 6 mm", StringComparison.Ordinal), "6 mm job planned");
        Driver.FindElement(By.CssSelector("#panel-layers summary")).Click();
        WaitFor(d => d.FindElements(By.Id("job-download")).Count == 1, "Download job file offered");

        // What the browser downloads, fetched as its link does (boot.js: with the tab's token), then handed to the file input.
        var json = (string)((IJavaScriptExecutor)Driver).ExecuteAsyncScript("""
            const done = arguments[arguments.length - 1];
            window.laserEngrave.fetch(document.getElementById('job-download').getAttribute('href')).then(r => r.text()).then(done, e => done('error ' + e));
            """)!;
        Assert.Contains("\"widthMm\": 6", json, StringComparison.Ordinal);
        var picked = Path.Combine(DataFolder, "picked", "qr-code.json");
        Directory.CreateDirectory(Path.GetDirectoryName(picked)!);
        File.WriteAllText(picked, json);
        SetField("widthMm", "3");
        WaitFor(d => d.FindElement(By.Id("status-estimate")).Text.StartsWith("3 × 3 mm", StringComparison.Ordinal), "3 mm job planned");

        Id("job-file").SendKeys(picked);

        WaitFor(d => d.FindElement(By.Id("status-estimate")).Text.StartsWith("6 × 6 mm", StringComparison.Ordinal), "the job file's 6 mm job opened");
        Assert.Empty(Driver.FindElements(By.CssSelector("#layer-list li")));
    }

    [Fact]
    public async Task FirstJob_SampleSizedDraggedRunPausedAbortedContinued_LogExported()
    {
        OpenSample("qr-code.bmp");
        Assert.Contains("41 × 41", Text("image-meta"), StringComparison.Ordinal);
        SetField("widthMm", "3");
        WaitFor(d => d.FindElement(By.Id("status-estimate")).Text.StartsWith("3 × 3 mm", StringComparison.Ordinal), "3 mm job planned");
        Assert.Equal(3, FieldValue("heightMm"));

        // Drag the job 10 mm to the right on the canvas: the origin follows, snapped to 0.01 mm.
        WaitFor(_ => View().Scale > 1, "the stage drawn");
        var (scale, ox, oy) = View();
        var canvas = Id("stage-canvas");
        var start = (X: ox + (2.5 * scale), Y: oy + (2.5 * scale));
        new Actions(Driver)
            .MoveToLocation((int)(canvas.Location.X + start.X), (int)(canvas.Location.Y + start.Y))
            .ClickAndHold().MoveByOffset((int)(10 * scale), 0).Release().Perform();
        WaitFor(_ => FieldValue("originXMm") > 9, "origin moved by the drag");
        var dragged = FieldValue("originXMm");
        Assert.InRange(dragged, 10, 12);
        Assert.Equal(Math.Round(dragged, 2), dragged);
        Assert.Equal(1, FieldValue("originYMm"));

        Id("connect").Click();
        WaitFor(d => d.FindElement(By.Id("machine-connection")).Text.Contains("simulator", StringComparison.Ordinal), "connected to the simulator");
        WaitFor(_ => Enabled("jog-x-"), "jog allowed");
        WaitFor(_ => Position().X is not null, "the position read");
        var before = Position();
        // The simulated stage starts at the far end of its travel: jog back from there.
        Id("jog-x-").Click();
        WaitFor(_ => Position().X < before.X - 0.09, "jogged 0.1 mm in X");
        WaitFor(_ => Enabled("jog-y-"), "jog done");
        new Actions(Driver).KeyDown(Keys.Shift).SendKeys(Keys.ArrowUp).KeyUp(Keys.Shift).Perform();
        WaitFor(_ => Position().Y < before.Y - 0.09, "jogged 0.1 mm in Y by Shift+arrow");
        Id("frame").Click();
        WaitFor(_ => Enabled("frame") && Enabled("start"), "frame traced");
        Assert.Empty(Driver.FindElements(By.Id("moves-error")));
        Id("sampleId").SendKeys("B-1" + Keys.Tab);

        // The simulator runs in virtual time, far faster than a person or the test's polling: the run is held (its
        // progress report waits, on the simulation's loop) once a twentieth is done, until the page's Pause has landed.
        using var pauseLanded = new ManualResetEventSlim();
        var run = Host.Services.GetRequiredService<MainViewModel>().Run;
        var held = 0;
        run.PropertyChanged += (_, e) =>
        {
            // Pausing is enough: the engine pauses after the current move, which is this very report's.
            if (e.PropertyName == nameof(RunViewModel.State) && run.State is RunState.Pausing or RunState.Paused)
            {
                pauseLanded.Set();
            }
            else if (e.PropertyName == nameof(RunViewModel.Progress) && run.Fraction >= 0.05 && Interlocked.Exchange(ref held, 1) == 0)
            {
                pauseLanded.Wait(TimeSpan.FromSeconds(60));
            }
        };
        Id("start").Click();
        WaitFor(_ => Progress() >= 5, "a twentieth done", 120);
        Id("pause").Click();
        WaitFor(d => d.FindElement(By.Id("status-run")).Text == "paused", "paused");
        var paused = Progress();

        // A window opened again shows the run where it is.
        Open();
        WaitFor(d => d.FindElement(By.Id("status-run")).Text == "paused", "the paused run shown in the new window");
        // Pause waits for the burn run under way, so the figure may still have grown a little.
        Assert.True(Progress() >= paused, $"progress {Progress()} % after reopening, {paused} % before");
        Assert.True(Enabled("resume") && Enabled("abort") && !Enabled("start"));
        Id("abort").Click();
        WaitFor(d => d.FindElement(By.Id("status-run")).Text == "aborted", "aborted");
        WaitFor(_ => Enabled("continue"), "the stopped run can be continued");
        Id("continue").Click();
        WaitFor(d => d.FindElement(By.Id("status-run")).Text == "completed", "continued run completed", 240);
        WaitFor(_ => Progress() == 100, "progress at 100 %");
        Assert.Contains("yes", Text("machine-homed"), StringComparison.Ordinal);

        // Zoom in on the job with the wheel, around the cursor, to see what burned.
        Resize(1440, 1000);
        canvas = Id("stage-canvas");
        (scale, ox, oy) = View();
        var centre = (X: ox + ((dragged + 1.5) * scale), Y: oy + (2.5 * scale));
        var wheelAt = new WheelInputDevice.ScrollOrigin
        {
            Element = canvas,
            XOffset = (int)(centre.X - (canvas.Size.Width / 2.0)),
            YOffset = (int)(centre.Y - (canvas.Size.Height / 2.0)),
        };
        for (var i = 0; i < 8; i++)
        {
            new Actions(Driver).ScrollFromOrigin(wheelAt, 0, -100).Perform();
        }

        WaitFor(_ => View().Scale > scale * 3, "zoomed in around the job");

        // Pan: drag the empty stage, and the job comes down into view.
        var unpanned = View();
        new Actions(Driver).MoveToElement(canvas, 0, 100).ClickAndHold().MoveByOffset(150, 250).Release().Perform();
        WaitFor(_ => View().Y > unpanned.Y + 200, "panned");
        Screenshot("workspace-run-completed");

        WaitFor(d => d.FindElements(By.Id("export-txt")).Count == 1, "the log can be exported");
        var href = Id("export-txt").GetAttribute("href")!;
        using var http = new HttpClient();
        http.DefaultRequestHeaders.Authorization = new("Bearer", Secret);
        var text = await http.GetStringAsync(new Uri(href), TestContext.Current.CancellationToken);
        Assert.Contains("B-1", text, StringComparison.Ordinal);
        Assert.DoesNotContain(Driver.Manage().Logs.GetLog(LogType.Browser), e => e.Level == LogLevel.Severe);
    }

    [Fact]
    public async Task OtherLocalServer_PageOpenInTheSameBrowser_ReceivesNoCredentialAndGetsNoHubConnection()
    {
        // Another program's server on another port of 127.0.0.1: it records every request the browser sends it, and its
        // page tries what a hostile page would (the app's hub over a WebSocket, its API) and reports what it got.
        var received = new System.Collections.Concurrent.ConcurrentQueue<string>();
        var report = new TaskCompletionSource<string>(TaskCreationOptions.RunContinuationsAsynchronously);
        var app = Url.TrimEnd('/');
        var other = WebApplication.CreateBuilder();
        other.WebHost.UseUrls("http://127.0.0.1:0");
        other.Configuration["Logging:LogLevel:Default"] = "Warning";
        await using var server = other.Build();
        server.Use(async (context, next) =>
        {
            received.Enqueue($"{context.Request.Method} {context.Request.Path}{context.Request.QueryString} " +
                string.Join("; ", context.Request.Headers.Select(h => $"{h.Key}: {h.Value}")));
            await next(context);
        });
        server.MapGet("/", () => Results.Content(
            $$"""
            <!DOCTYPE html><html><body><img src="/probe.png"><script>
            const app = '{{app}}';
            const results = {};
            const socket = new WebSocket(app.replace('http://', 'ws://') + '/_blazor');
            const hub = new Promise(done => { socket.onopen = () => done('open'); socket.onerror = () => done('refused'); });
            const negotiate = fetch(app + '/_blazor/negotiate?negotiateVersion=1', { method: 'POST', credentials: 'include' })
              .then(r => 'answered ' + r.status, () => 'blocked');
            const fire = fetch(app + '/api/moves/fire', { method: 'POST', mode: 'no-cors', credentials: 'include', body: '{"pulses":1}' })
              .then(() => 'sent', () => 'blocked');
            Promise.all([hub, negotiate, fire]).then(([h, n, f]) => fetch('/report?hub=' + h + '&negotiate=' + encodeURIComponent(n) + '&fire=' + f));
            </script></body></html>
            """, "text/html"));
        server.MapGet("/report", (HttpRequest request) =>
        {
            report.TrySetResult(request.QueryString.Value ?? string.Empty);
            return Results.Ok();
        });
        await server.StartAsync(TestContext.Current.CancellationToken);
        var otherUrl = server.Services.GetRequiredService<IServer>().Features.Get<IServerAddressesFeature>()!.Addresses.First();
        var appWindow = Driver.CurrentWindowHandle;
        var windows = Host.Services.GetRequiredService<WindowLifetime>();
        Assert.Equal(1, windows.OpenWindows);

        Driver.SwitchTo().NewWindow(WindowType.Tab);
        Driver.Navigate().GoToUrl(otherUrl);
        var outcome = await report.Task.WaitAsync(TimeSpan.FromSeconds(60), TestContext.Current.CancellationToken);

        Assert.Contains("hub=refused", outcome, StringComparison.Ordinal);
        Assert.Contains("fire=", outcome, StringComparison.Ordinal);
        Assert.DoesNotContain("answered 200", Uri.UnescapeDataString(outcome), StringComparison.Ordinal);
        Assert.Contains(received, r => r.StartsWith("GET /probe.png", StringComparison.Ordinal));
        Assert.DoesNotContain(received, r => r.Contains(Secret, StringComparison.Ordinal));
        Assert.DoesNotContain(received, r => r.Contains("LaserEngrave", StringComparison.OrdinalIgnoreCase));
        Assert.Equal(1, windows.OpenWindows);
        Assert.Equal("off", Host.Services.GetRequiredService<MainViewModel>().Machine.Connection is null ? "off" : "connected");

        // The app's own window still works.
        Driver.SwitchTo().Window(appWindow);
        OpenSample("qr-code.bmp");
    }

    [Fact]
    public void Page_ReloadedKeepsTheToken_ANewTabOrAStaleTokenIsToldToOpenThePrintedAddress()
    {
        // The launch code left the address bar, no address ever held the token and no cookie holds it: the tab's
        // sessionStorage does.
        Assert.DoesNotContain("token", Driver.Url, StringComparison.Ordinal);
        Assert.DoesNotContain("launch", Driver.Url, StringComparison.Ordinal);
        Assert.DoesNotContain(Driver.Manage().Cookies.AllCookies, c => c.Value.Contains(Secret, StringComparison.Ordinal));
        Driver.Navigate().Refresh();
        WaitFor(d => d.FindElement(By.Id("app")).GetAttribute("data-interactive") == "true", "the reloaded page is interactive");

        // A tab opened by hand has no token: one line says what to do, and no connection is made.
        var windows = Host.Services.GetRequiredService<WindowLifetime>();
        Driver.SwitchTo().NewWindow(WindowType.Tab);
        Driver.Navigate().GoToUrl(Url);
        WaitFor(d => d.FindElement(By.Id("no-token")).Text.Contains("printed", StringComparison.Ordinal), "told to open the printed address");
        Assert.Equal(1, windows.OpenWindows);

        // The launch address again (as the history or a synced profile keeps it): its code was used, so nothing opens.
        Driver.ExecuteScript("sessionStorage.clear();");
        Driver.Navigate().GoToUrl("about:blank");
        Driver.Navigate().GoToUrl(LaunchAddress);
        WaitFor(d => d.FindElements(By.Id("no-token")).Count == 1, "a used launch address told to open the app from its window");
        Assert.Equal(1, windows.OpenWindows);

        // A token of an earlier start (the app restarted on the same port): refused, then the same line.
        Driver.ExecuteScript("sessionStorage.setItem('laserengrave-token', 'an-earlier-start');");
        Driver.Navigate().Refresh();
        WaitFor(d => d.FindElements(By.Id("no-token")).Count == 1, "a stale token told to open the printed address");
        Assert.Null(Driver.ExecuteScript("return sessionStorage.getItem('laserengrave-token');"));
        Assert.Equal(1, windows.OpenWindows);
    }

    [Fact]
    public void Drawing_SampleOpened_ItsStrokesDrawnOnTheStageWithTheEstimate()
    {
        Resize(1440, 1000);
        SetField("widthMm", "20");
        SetField("originXMm", "10");
        SetField("originYMm", "10");
        WaitFor(d => d.FindElements(By.CssSelector("#samples button[data-path$='hexagons.dxf']")).Count == 1, "hexagons.dxf offered");
        Driver.FindElement(By.CssSelector("#samples button[data-path$='hexagons.dxf']")).Click();
        WaitFor(d => d.FindElement(By.Id("drawing-meta")).Text.Contains("strokes", StringComparison.Ordinal), "the drawing planned");
        WaitFor(d => int.Parse(d.FindElement(By.Id("stage-host")).GetAttribute("data-drawn-moves") ?? "0", CultureInfo.InvariantCulture) > 0, "its strokes drawn");

        Id("zoom-in").Click();
        Id("zoom-in").Click();
        var path = Screenshot("drawing-on-stage");

        Assert.True(File.Exists(path));
        Assert.Contains("mm to burn", Text("drawing-meta"), StringComparison.Ordinal);
        Assert.Empty(Driver.FindElements(By.Id("no-image")));
    }

    [Fact]
    public void Drawing_FramedThenRunAbortedAndContinued_TheRunBarShowsTheFrameAndTheRun()
    {
        Size1280x720();
        WaitFor(d => d.FindElements(By.CssSelector("#samples button[data-path$='hexagons.dxf']")).Count == 1, "hexagons.dxf offered");
        Driver.FindElement(By.CssSelector("#samples button[data-path$='hexagons.dxf']")).Click();
        WaitFor(d => d.FindElement(By.Id("drawing-meta")).Text.Contains("strokes", StringComparison.Ordinal), "the drawing planned");
        Id("connect").Click();
        WaitFor(_ => Enabled("frame") && Enabled("goto-origin"), "Frame and Job origin offered for the drawing");
        ZoomAround(3.5, 3.5, 6);

        // The twin runs in virtual time: the frame is held (its position reading waits on the simulation's loop) once
        // the laser's cross traces the drawing's box, until the page has shown it under way.
        var main = Host.Services.GetRequiredService<MainViewModel>();
        using var shown = new ManualResetEventSlim();
        var heldFrame = 0;
        main.Machine.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(MachineViewModel.YMicrosteps) && main.Machine.Activity.Current?.Kind == App.Services.MachineOperationKind.TestMove
                && main.Machine.XMicrosteps * main.Machine.Profile.X.MicrostepUm / 1000 is > 4 and < 6.5
                && main.Machine.YMicrosteps * main.Machine.Profile.Y.MicrostepUm / 1000 is > 2 and < 6.5
                && Interlocked.Exchange(ref heldFrame, 1) == 0)
            {
                shown.Wait(TimeSpan.FromSeconds(60));
            }
        };
        Id("frame").Click();
        WaitFor(d => d.FindElement(By.Id("status-run")).Text.Contains("Tracing the job's frame, laser off", StringComparison.Ordinal), "the frame shown in the run bar");
        Assert.True(Id("runbar-stop").Displayed && Enabled("runbar-stop"));
        Assert.True(new FileInfo(Screenshot("frame-under-way")).Length > 20_000);
        shown.Set();
        WaitFor(_ => Enabled("frame") && Enabled("start"), "the frame traced");
        Assert.Empty(Driver.FindElements(By.Id("moves-error")));
        Assert.Equal("idle", Text("status-run"));

        // The run is held a third of the way until the page's Abort has landed, then continued to its end.
        using var abortLanded = new ManualResetEventSlim();
        var held = 0;
        main.Run.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(RunViewModel.State) && main.Run.State is RunState.Aborting)
            {
                abortLanded.Set();
            }
            else if (e.PropertyName == nameof(RunViewModel.Progress) && main.Run.Fraction >= 0.3 && Interlocked.Exchange(ref held, 1) == 0)
            {
                abortLanded.Wait(TimeSpan.FromSeconds(60));
            }
        };
        Id("start").Click();
        WaitFor(_ => Progress() >= 30, "a third of the drawing burned", 120);
        Id("abort").Click();
        WaitFor(d => d.FindElement(By.Id("status-run")).Text == "aborted", "aborted");
        WaitFor(_ => Enabled("continue"), "the stopped drawing can be continued");
        Id("continue").Click();
        WaitFor(d => d.FindElement(By.Id("status-run")).Text == "completed", "the continued drawing completed", 240);
        Assert.Equal(100, Progress());

        // Both runs in the history table, ticked for the export.
        Id("open-history").Click();
        WaitFor(d => d.FindElements(By.CssSelector("#history-table tbody tr")).Count == 2, "both runs in the history");
        Id("history-select-shown").Click();
        WaitFor(d => d.FindElements(By.Id("history-csv")).Count == 1, "the export offered");
        Assert.True(new FileInfo(Screenshot("run-history")).Length > 20_000);

        // A run's Log link opens its text in a new window, fetched with the token (the new window has none of its own).
        var workspace = Driver.CurrentWindowHandle;
        Driver.FindElement(By.CssSelector("#history-table tbody tr a.chip[target='_blank']")).Click();
        WaitFor(d => d.WindowHandles.Count == 2, "the log's window opened");
        Driver.SwitchTo().Window(Driver.WindowHandles.Single(h => h != workspace));
        WaitFor(d => d.FindElement(By.TagName("body")).Text.Contains("Outcome", StringComparison.OrdinalIgnoreCase), "the log's text shown");
        Driver.Close();
        Driver.SwitchTo().Window(workspace);
        Id("history-close").Click();
        Assert.DoesNotContain(Driver.Manage().Logs.GetLog(LogType.Browser), e => e.Level == LogLevel.Severe);
    }

    [Fact]
    public void Sweep_Run_TheRunBarCountsItsCells()
    {
        Size1280x720();
        Driver.FindElement(By.CssSelector("#panel-sweep summary")).Click();
        SetField("sweepCellMm", "0.5");
        SetField("sweepSpacingMm", "0.3");
        WaitFor(d => d.FindElement(By.Id("sweep-summary")).Text.StartsWith("3 × 3 cells", StringComparison.Ordinal), "a 3 x 3 sweep planned");
        Id("connect").Click();
        Id("sweepShow").Click();
        WaitFor(_ => Enabled("start") && Id("runs-sweep").Displayed, "Start runs the sweep shown");
        WaitFor(d => d.FindElement(By.Id("status-estimate")).Text.StartsWith("sweep 3 × 3 cells", StringComparison.Ordinal), "the header names the sweep");
        ZoomAround(2.5, 2.5, 8);

        // Held at its fifth cell (virtual time) until the page has shown it.
        var sweep = Host.Services.GetRequiredService<MainViewModel>().Sweep;
        using var shown = new ManualResetEventSlim();
        var held = 0;
        sweep.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(SweepViewModel.Progress) && sweep.ProgressText?.StartsWith("cell 5 of 9", StringComparison.Ordinal) == true
                && sweep.Progress!.Run.MovesDone > 10 && Interlocked.Exchange(ref held, 1) == 0)
            {
                shown.Wait(TimeSpan.FromSeconds(60));
            }
        };
        Id("start").Click();
        WaitFor(d => d.FindElement(By.Id("progress-figures")).Text.StartsWith("cell 5 of 9: row 2, column 2 (speed 1 mm/s, frequency 1000 Hz)", StringComparison.Ordinal), "the fifth cell in the run bar", 120);

        Assert.Equal("sweep running", Text("status-run"));
        Assert.InRange(Progress(), 40, 60);
        Assert.True(Enabled("abort"));
        Assert.Contains("left", Text("time-left"), StringComparison.Ordinal);
        Driver.ExecuteScript("document.getElementById('panel-sweep').scrollIntoView();");
        Assert.True(new FileInfo(Screenshot("sweep-under-way")).Length > 20_000);
        shown.Set();
        WaitFor(d => d.FindElement(By.Id("sweep-status")).Text.StartsWith("completed: 9 of 9 cells", StringComparison.Ordinal), "the sweep completed", 240);
        Assert.Equal("idle", Text("status-run"));
        Assert.DoesNotContain(Driver.Manage().Logs.GetLog(LogType.Browser), e => e.Level == LogLevel.Severe);
    }

    [Fact]
    public void Layers_SampleJobOpenedAndRunOnTheTwin_EachLayerDrawnAndTheRunCompletes()
    {
        Resize(1440, 1000);
        // The Layers panel stays folded until there are layers.
        Driver.FindElement(By.CssSelector("#panel-layers summary")).Click();
        WaitFor(d => d.FindElements(By.CssSelector("#layer-samples button[data-path$='plate.json']")).Count == 1, "plate.json offered");
        Driver.FindElement(By.CssSelector("#layer-samples button[data-path$='plate.json']")).Click();
        WaitFor(d => d.FindElement(By.Id("layers-total")).Text.StartsWith("3 layers", StringComparison.Ordinal), "the layers planned");
        WaitFor(d => int.Parse(d.FindElement(By.Id("stage-host")).GetAttribute("data-drawn-moves") ?? "0", CultureInfo.InvariantCulture) > 0, "the layers drawn");
        Assert.StartsWith("3 layers", Text("status-estimate"), StringComparison.Ordinal);
        Assert.True(Id("runs-layers").Displayed);

        Id("connect").Click();
        WaitFor(d => d.FindElement(By.Id("machine-connection")).Text.Contains("simulator", StringComparison.Ordinal), "connected to the simulator");
        WaitFor(_ => Enabled("start"), "the layers can start");
        Id("start").Click();
        WaitFor(d => d.FindElement(By.Id("status-run")).Text == "completed", "the layers' run completed", 240);

        Assert.Equal("layer 3 of 3 “cut”", Text("progress-layer"));
        Assert.Equal(100, Progress());
        Id("zoom-in").Click();
        Driver.ExecuteScript("document.getElementById('layer-list').scrollIntoView({ block: 'center' });");
        Assert.True(new FileInfo(Screenshot("layers-on-stage")).Length > 20_000);
        Assert.DoesNotContain(Driver.Manage().Logs.GetLog(LogType.Browser), e => e.Level == LogLevel.Severe);
    }

    [Fact]
    public void Window_Closed_AppEnds()
    {
        var stopping = Host.Lifetime.ApplicationStopping;
        Assert.Equal(1, Host.Services.GetRequiredService<WindowLifetime>().OpenWindows);
        Assert.False(stopping.IsCancellationRequested);

        // Leaving the page drops its connection, as closing the window does.
        Driver.Navigate().GoToUrl("about:blank");

        WaitFor(_ => stopping.IsCancellationRequested, "the app ending after its window closed");
    }

    [Fact]
    public void Job_ResizedTwice_CtrlZUndoesCtrlYRedoes()
    {
        OpenSample("qr-code.bmp");
        SetField("widthMm", "3");
        WaitFor(d => d.FindElement(By.Id("status-estimate")).Text.StartsWith("3 × 3 mm", StringComparison.Ordinal), "3 mm job planned");
        SetField("widthMm", "7");
        WaitFor(d => d.FindElement(By.Id("status-estimate")).Text.StartsWith("7 × 7 mm", StringComparison.Ordinal), "7 mm job planned");
        Driver.FindElement(By.ClassName("brand")).Click();

        new Actions(Driver).KeyDown(Keys.Control).SendKeys("z").KeyUp(Keys.Control).Perform();
        WaitFor(d => d.FindElement(By.Id("status-estimate")).Text.StartsWith("3 × 3 mm", StringComparison.Ordinal), "Ctrl+Z: 3 mm again");
        Assert.Equal(3, FieldValue("widthMm"));

        new Actions(Driver).KeyDown(Keys.Control).SendKeys("y").KeyUp(Keys.Control).Perform();
        WaitFor(d => d.FindElement(By.Id("status-estimate")).Text.StartsWith("7 × 7 mm", StringComparison.Ordinal), "Ctrl+Y: 7 mm again");
        Assert.False(Enabled("redo"));
        Id("undo").Click();
        WaitFor(d => d.FindElement(By.Id("status-estimate")).Text.StartsWith("3 × 3 mm", StringComparison.Ordinal), "Undo: 3 mm again");
    }
}
