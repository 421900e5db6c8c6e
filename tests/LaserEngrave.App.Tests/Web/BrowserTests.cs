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

/// <summary>The workspace in headless Chromium against the app on a real port, the simulator in virtual time.</summary>
/// <remarks>No sleeps: every step waits for a condition the page shows.</remarks>
public sealed class BrowserTests : IAsyncLifetime
{
    private const string ChromiumPath = "/usr/bin/chromium";
    private const string DriverFolder = "/usr/bin";

    private readonly TestFiles.TempFolder _folder = TestFiles.NewFolder();
    private readonly TestFiles.TempFolder _profile = TestFiles.NewFolder();
    private WebApplication? _app;
    private ChromeDriver? _driver;
    private string _url = string.Empty;
    private string _token = string.Empty;

    private ChromeDriver Driver => _driver ?? throw new InvalidOperationException("not started");

    /// <summary>Screenshots land here (the test output folder); docs/images takes them from there.</summary>
    public static string ScreenshotFolder => Path.Combine(AppContext.BaseDirectory, "screenshots");

    /// <summary>How long the app outlives its window in these tests (the app opened "its own window": the test's browser).</summary>
    private static readonly TimeSpan IdleExit = TimeSpan.FromMilliseconds(300);

    public async ValueTask InitializeAsync()
    {
        _app = AppHost.Build([], "http://127.0.0.1:0", services =>
        {
            AppFactory.UseTestServices(services, _folder.Path);
            // Only the test of the window's end lets the app end; the others reload the page at will.
            services.AddSingleton(new WindowLifetimeOptions(TestContext.Current.TestMethod?.MethodName == nameof(Window_Closed_AppEnds) ? IdleExit : null));
        });
        await _app.StartAsync(TestContext.Current.CancellationToken);
        _url = _app.Services.GetRequiredService<IServer>().Features.Get<IServerAddressesFeature>()!.Addresses.First();
        _token = _app.Services.GetRequiredService<AccessToken>().Value;

        var options = new ChromeOptions { BinaryLocation = ChromiumPath };
        options.AddArguments(
            "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking",
            "--disable-component-update", "--disable-sync", "--disable-dev-shm-usage", "--window-size=1280,720", "--user-data-dir=" + _profile.Path);
        options.SetLoggingPreference(LogType.Browser, LogLevel.Severe);
        var service = ChromeDriverService.CreateDefaultService(DriverFolder, "chromedriver");
        service.HideCommandPromptWindow = true;
        service.SuppressInitialDiagnosticInformation = true;
        _driver = new ChromeDriver(service, options, TimeSpan.FromSeconds(60));
        Open();
    }

    public async ValueTask DisposeAsync()
    {
        _driver?.Quit();
        _driver?.Dispose();
        if (_app is not null)
        {
            await _app.StopAsync(CancellationToken.None);
            await _app.DisposeAsync();
        }

        _profile.Dispose();
        _folder.Dispose();
    }

    /// <summary>Opens the address the app prints: the first load shows the start's token, which the page keeps as a cookie.</summary>
    private void Open()
    {
        Driver.Navigate().GoToUrl($"{_url.TrimEnd('/')}/?{AccessToken.QueryName}={_token}");
        WaitFor(d => d.FindElement(By.Id("app")).GetAttribute("data-interactive") == "true", "the page is interactive");
        WaitFor(d => d.FindElement(By.Id("stage-host")).GetAttribute("data-ready") == "true", "the stage canvas is ready");
    }

    private IWebElement Id(string id) => Driver.FindElement(By.Id(id));

    private void WaitFor(Func<IWebDriver, bool> condition, string what, double seconds = 30)
    {
        var wait = new WebDriverWait(Driver, TimeSpan.FromSeconds(seconds)) { Message = "waiting for: " + what };
        wait.IgnoreExceptionTypes(typeof(NoSuchElementException), typeof(StaleElementReferenceException));
        try
        {
            wait.Until(condition);
        }
        catch (WebDriverTimeoutException)
        {
            Screenshot("failed-" + string.Concat(what.Where(char.IsLetterOrDigit)));
            throw;
        }
    }

    private string Text(string id) => Id(id).Text;

    private void SetField(string id, string value)
    {
        var input = Id(id);
        input.Clear();
        input.SendKeys(value + Keys.Tab);
    }

    private void OpenSample(string name)
    {
        WaitFor(d => d.FindElements(By.CssSelector($"#samples button[data-path$='{name}']")).Count == 1, name + " offered");
        Driver.FindElement(By.CssSelector($"#samples button[data-path$='{name}']")).Click();
        WaitFor(d => d.FindElement(By.Id("image-meta")).Text.Contains(name, StringComparison.Ordinal), name + " open");
    }

    private bool Enabled(string id) => Id(id).GetAttribute("disabled") is null;

    private double Progress() => double.Parse(Text("progress-text").TrimEnd('%', ' '), CultureInfo.InvariantCulture);

    private string Screenshot(string name)
    {
        Directory.CreateDirectory(ScreenshotFolder);
        var path = Path.Combine(ScreenshotFolder, name + ".png");
        Driver.GetScreenshot().SaveAsFile(path);
        return path;
    }

    private long HorizontalOverflow() => Convert.ToInt64(
        Driver.ExecuteScript("return document.documentElement.scrollWidth - document.documentElement.clientWidth;"), CultureInfo.InvariantCulture);

    private void Resize(int width, int height)
    {
        Driver.Manage().Window.Size = new System.Drawing.Size(width, height);
        WaitFor(d => Convert.ToInt64(((IJavaScriptExecutor)d).ExecuteScript("return window.innerWidth;"), CultureInfo.InvariantCulture) <= width, $"window {width} wide");
    }

    /// <summary>The stage's view (px per mm, offset) as the canvas last drew it.</summary>
    private (double Scale, double X, double Y) View()
    {
        var parts = Id("stage-host").GetAttribute("data-view")!.Split(',').Select(p => double.Parse(p, CultureInfo.InvariantCulture)).ToArray();
        return (parts[0], parts[1], parts[2]);
    }

    /// <summary>The laser's position as the jog pad shows it, mm.</summary>
    private (double? X, double? Y) Position()
    {
        var parts = Text("position").Replace("mm", "", StringComparison.Ordinal).Split(['X', 'Y', '·'], StringSplitOptions.RemoveEmptyEntries | StringSplitOptions.TrimEntries);
        static double? Number(string text) => double.TryParse(text, NumberStyles.Float, CultureInfo.InvariantCulture, out var v) ? v : null;
        return parts.Length == 2 ? (Number(parts[0]), Number(parts[1])) : (null, null);
    }

    private double FieldValue(string id) => double.Parse(Id(id).GetDomProperty("value")!, CultureInfo.InvariantCulture);

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
        Driver.FindElement(By.TagName("body")).SendKeys(Keys.ArrowUp);
        WaitFor(_ => Position().Y < before.Y - 0.09, "jogged 0.1 mm in Y by the arrow key");
        Id("frame").Click();
        WaitFor(_ => Enabled("frame") && Enabled("start"), "frame traced");
        Assert.Empty(Driver.FindElements(By.Id("moves-error")));
        Id("sampleId").SendKeys("B-1" + Keys.Tab);

        // The simulator runs in virtual time, far faster than a person or the test's polling: the run is held (its
        // progress report waits, on the simulation's loop) once a twentieth is done, until the page's Pause has landed.
        using var pauseLanded = new ManualResetEventSlim();
        var run = _app!.Services.GetRequiredService<MainViewModel>().Run;
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
        http.DefaultRequestHeaders.Authorization = new("Bearer", _token);
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
        var app = _url.TrimEnd('/');
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
        var windows = _app!.Services.GetRequiredService<WindowLifetime>();
        Assert.Equal(1, windows.OpenWindows);

        Driver.SwitchTo().NewWindow(WindowType.Tab);
        Driver.Navigate().GoToUrl(otherUrl);
        var outcome = await report.Task.WaitAsync(TimeSpan.FromSeconds(60), TestContext.Current.CancellationToken);

        Assert.Contains("hub=refused", outcome, StringComparison.Ordinal);
        Assert.Contains("fire=", outcome, StringComparison.Ordinal);
        Assert.DoesNotContain("answered 200", Uri.UnescapeDataString(outcome), StringComparison.Ordinal);
        Assert.Contains(received, r => r.StartsWith("GET /probe.png", StringComparison.Ordinal));
        Assert.DoesNotContain(received, r => r.Contains(_token, StringComparison.Ordinal));
        Assert.DoesNotContain(received, r => r.Contains("LaserEngrave", StringComparison.OrdinalIgnoreCase));
        Assert.Equal(1, windows.OpenWindows);
        Assert.Equal("off", _app.Services.GetRequiredService<MainViewModel>().Machine.Connection is null ? "off" : "connected");

        // The app's own window still works.
        Driver.SwitchTo().Window(appWindow);
        OpenSample("qr-code.bmp");
    }

    [Fact]
    public void Page_ReloadedKeepsTheToken_ANewTabOrAStaleTokenIsToldToOpenThePrintedAddress()
    {
        // The token left the address bar and no cookie holds it: the tab's sessionStorage does.
        Assert.DoesNotContain("token", Driver.Url, StringComparison.Ordinal);
        Assert.DoesNotContain(Driver.Manage().Cookies.AllCookies, c => c.Value.Contains(_token, StringComparison.Ordinal));
        Driver.Navigate().Refresh();
        WaitFor(d => d.FindElement(By.Id("app")).GetAttribute("data-interactive") == "true", "the reloaded page is interactive");

        // A tab opened by hand has no token: one line says what to do, and no connection is made.
        var windows = _app!.Services.GetRequiredService<WindowLifetime>();
        Driver.SwitchTo().NewWindow(WindowType.Tab);
        Driver.Navigate().GoToUrl(_url);
        WaitFor(d => d.FindElement(By.Id("no-token")).Text.Contains("printed", StringComparison.Ordinal), "told to open the printed address");
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

    /// <summary>The page's own area at exactly 1280 x 720, as docs/user-guide.md shows it.</summary>
    private void Size1280x720()
    {
        Driver.ExecuteCdpCommand("Emulation.setDeviceMetricsOverride", new Dictionary<string, object?>
        {
            ["width"] = 1280, ["height"] = 720, ["deviceScaleFactor"] = 1, ["mobile"] = false,
        });
        WaitFor(d => Convert.ToInt64(((IJavaScriptExecutor)d).ExecuteScript("return window.innerHeight;"), CultureInfo.InvariantCulture) == 720, "a 1280 x 720 page");
    }

    /// <summary>Zooms the stage in with the wheel around (<paramref name="xMm"/>, <paramref name="yMm"/>), to show a small job.</summary>
    private void ZoomAround(double xMm, double yMm, int steps)
    {
        WaitFor(_ => View().Scale > 1, "the stage drawn");
        var canvas = Id("stage-canvas");
        var (scale, ox, oy) = View();
        var at = new WheelInputDevice.ScrollOrigin
        {
            Element = canvas,
            XOffset = (int)(ox + (xMm * scale) - (canvas.Size.Width / 2.0)),
            YOffset = (int)(oy + (yMm * scale) - (canvas.Size.Height / 2.0)),
        };
        for (var i = 0; i < steps; i++)
        {
            new Actions(Driver).ScrollFromOrigin(at, 0, -100).Perform();
        }

        WaitFor(_ => View().Scale > scale * 2, "zoomed in");

        // Then the job towards the middle: drag the empty stage right and down (the job lies near the top-left corner).
        var zoomed = View();
        new Actions(Driver).MoveToElement(canvas, 150, 150).ClickAndHold().MoveByOffset(130, 90).Release().Perform();
        WaitFor(_ => View().X > zoomed.X + 100, "panned");
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
        var main = _app!.Services.GetRequiredService<MainViewModel>();
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
        WaitFor(_ => Enabled("sweepRun"), "the sweep can run");
        Id("sweepShow").Click();
        ZoomAround(2.5, 2.5, 8);

        // Held at its fifth cell (virtual time) until the page has shown it.
        var sweep = _app!.Services.GetRequiredService<MainViewModel>().Sweep;
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
        Id("sweepRun").Click();
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

    private int DrawnMoves() => int.Parse(Driver.FindElement(By.Id("stage-host")).GetAttribute("data-drawn-moves") ?? "0", CultureInfo.InvariantCulture);

    [Fact]
    public void Workspace_CommonWindowSizes_NoHorizontalScrolling()
    {
        OpenSample("text-banner.png");
        foreach (var (width, height) in new[] { (1280, 720), (1920, 1080), (800, 600) })
        {
            Resize(width, height);
            Assert.True(HorizontalOverflow() <= 0, $"at {width} x {height} the page scrolls sideways by {HorizontalOverflow()} px");
            Assert.True(Id("runbar").Displayed && Id("stage-canvas").Displayed);
        }
    }

    [Fact]
    public void Workspace_NarrowWindowScrolledDown_AbortAndRunStateStayInView()
    {
        OpenSample("text-banner.png");
        foreach (var (width, height) in new[] { (1000, 700), (1099, 700), (1000, 800), (1280, 700) })
        {
            Resize(width, height);
            Driver.ExecuteScript("window.scrollTo(0, document.documentElement.scrollHeight);");
            foreach (var id in new[] { "abort", "status-run" })
            {
                var inView = (bool)Driver.ExecuteScript(
                    """
                    const r = arguments[0].getBoundingClientRect();
                    return r.height > 0 && r.top >= 0 && r.bottom <= window.innerHeight && r.left >= 0 && r.right <= window.innerWidth;
                    """, Id(id))!;
                Assert.True(inView, $"at {width} x {height} scrolled down, #{id} is off-screen");
            }
        }
    }

    /// <summary>Waits until the theme's colour transitions have ended (endless animations, a busy spinner, do not count).</summary>
    private void ColoursSettled() => WaitFor(
        d => Convert.ToInt64(((IJavaScriptExecutor)d).ExecuteScript(
            "return document.getAnimations().filter(a => a.effect && a.effect.getTiming().iterations !== Infinity).length;"), CultureInfo.InvariantCulture) == 0,
        "colours settled");

    /// <summary>The contrast ratio (WCAG) of an element's text against the first opaque background behind it.</summary>
    private double Contrast(string selector) => Convert.ToDouble(Driver.ExecuteScript(
        """
        const el = document.querySelector(arguments[0]);
        const rgba = s => { const v = s.match(/[\d.]+/g).map(Number); return v.length === 3 ? [...v, 1] : v; };
        let bg = [255, 255, 255, 1];
        for (let e = el; e; e = e.parentElement) {
          const c = rgba(getComputedStyle(e).backgroundColor);
          if (c[3] > 0) { bg = c; break; }
        }
        const fgRaw = rgba(getComputedStyle(el).color), op = Number(getComputedStyle(el).opacity);
        const a = fgRaw[3] * op;
        const fg = fgRaw.slice(0, 3).map((v, i) => v * a + bg[i] * (1 - a));
        const lum = c => c.slice(0, 3).map(v => { v /= 255; return v <= 0.03928 ? v / 12.92 : Math.pow((v + 0.055) / 1.055, 2.4); })
          .reduce((s, v, i) => s + v * [0.2126, 0.7152, 0.0722][i], 0);
        const [x, y] = [lum(fg), lum(bg)];
        return (Math.max(x, y) + 0.05) / (Math.min(x, y) + 0.05);
        """, selector), CultureInfo.InvariantCulture);

    [Fact]
    public void Theme_SwitchedDarkAndLight_PageFollowsSettingsKeepItDisabledControlsDimmed()
    {
        OpenSample("qr-code.bmp");
        var main = _app!.Services.GetRequiredService<MainViewModel>();
        Assert.Equal("system", main.Settings.Theme);
        string? BodyTheme() => (string?)Driver.ExecuteScript("return document.body.getAttribute('data-theme');");

        // A test move holds the machine: the job's controls and most machine buttons are disabled, the view's are not.
        using (main.Activity.Begin(App.Services.MachineOperation.TestMove("a theme check")))
        {
            WaitFor(d => d.FindElement(By.CssSelector("#samples button.chip")).GetAttribute("disabled") is not null, "the job's controls disabled");
            foreach (var theme in new[] { "dark", "light" })
            {
                Driver.FindElement(By.CssSelector($"#theme option[value='{theme}']")).Click();
                WaitFor(_ => (BodyTheme() == "dark") == (theme == "dark"), theme + " applied");
                WaitFor(_ => main.Settings.Theme == theme, theme + " kept in the settings");
                ColoursSettled();

                // Enabled controls keep their text readable (WCAG 4.5:1); disabled ones are dimmed well below it.
                foreach (var enabled in new[] { "#zoom-fit", "#theme", "#sampleId", ".steps .chip:not(.on)" })
                {
                    Assert.True(Contrast(enabled) >= 4.5, $"{theme}: enabled {enabled} has contrast {Contrast(enabled):0.00}");
                }

                foreach (var disabled in new[] { "#disconnect", "#start", "#samples button.chip", "#widthMm", "#dither", "#aspectLocked" })
                {
                    Assert.True(Id("app").FindElement(By.CssSelector(disabled)).GetAttribute("disabled") is not null, $"{disabled} disabled");
                    Assert.True(Contrast(disabled == "#aspectLocked" ? "label.check:has(#aspectLocked)" : disabled) <= 3, $"{theme}: disabled {disabled} has contrast {Contrast(disabled):0.00}");
                }
            }
        }

        // The settings, not the browser's storage, decide the theme of a window opened again.
        Driver.FindElement(By.CssSelector("#theme option[value='dark']")).Click();
        WaitFor(_ => main.Settings.Theme == "dark", "dark kept in the settings");
        Driver.ExecuteScript("localStorage.clear();");
        Open();
        WaitFor(_ => BodyTheme() == "dark", "dark again after reopening");
        Assert.Equal("dark", Id("theme").GetDomProperty("value"));
        Driver.FindElement(By.CssSelector("#theme option[value='system']")).Click();
        WaitFor(_ => BodyTheme() is null, "the system's (light) mode");
    }

    [Fact]
    public void Workspace_LightAndDark_Screenshots()
    {
        // The page's own area at exactly 1280 x 720, as docs/user-guide.md shows it.
        Driver.ExecuteCdpCommand("Emulation.setDeviceMetricsOverride", new Dictionary<string, object?>
        {
            ["width"] = 1280, ["height"] = 720, ["deviceScaleFactor"] = 1, ["mobile"] = false,
        });
        WaitFor(d => Convert.ToInt64(((IJavaScriptExecutor)d).ExecuteScript("return window.innerHeight;"), CultureInfo.InvariantCulture) == 720, "a 1280 x 720 page");
        OpenSample("qr-code.bmp");
        SetField("widthMm", "12");
        WaitFor(d => d.FindElement(By.Id("status-estimate")).Text.StartsWith("12 × 12 mm", StringComparison.Ordinal), "12 mm job planned");
        Id("connect").Click();
        WaitFor(d => d.FindElement(By.Id("machine-homed")).Displayed && Enabled("jog-x-"), "connected to the simulator, state read");
        WaitFor(d => d.FindElement(By.Id("stage-host")).GetAttribute("data-drawn-moves") != "0", "plan drawn");
        foreach (var theme in new[] { "light", "dark" })
        {
            Driver.FindElement(By.CssSelector($"#theme option[value='{theme}']")).Click();
            WaitFor(d => ((string?)((IJavaScriptExecutor)d).ExecuteScript("return document.body.getAttribute('data-theme');") == "dark") == (theme == "dark"), theme + " applied");
            ColoursSettled();
            // The stage redraws on the theme's change event, at the next frame.
            Driver.ExecuteAsyncScript("requestAnimationFrame(() => requestAnimationFrame(arguments[arguments.length - 1]));");
            var path = Screenshot("workspace-" + theme);
            Assert.True(new FileInfo(path).Length > 20_000);
        }
    }

    [Fact]
    public void FocalSeries_ProfileWithZ_PresetPlannedAndShown()
    {
        Resize(1440, 1000);
        Driver.FindElement(By.CssSelector("#panel-sweep summary")).Click();
        WaitFor(d => d.FindElement(By.Id("sweep-focus-note")).Text.Contains("no Z axis", StringComparison.Ordinal), "focus not offered on two axes");
        var path = Path.Combine(_folder.Path, "three-axis.json");
        var profile = Core.Geometry.MachineProfile.Default with { Z = new Core.Geometry.ZAxisProfile() };
        profile.Save(path);

        _app!.Services.GetRequiredService<MainViewModel>().UseProfile(path, profile);
        WaitFor(d => d.FindElements(By.Id("sweepFocalSeries")).Count == 1, "the focal series offered");
        Id("sweepFocalSeries").Click();

        WaitFor(d => d.FindElement(By.Id("sweep-summary")).Text.StartsWith("9 × 1 cells", StringComparison.Ordinal), "the focal series planned");
        Driver.ExecuteScript("document.getElementById('panel-sweep').scrollIntoView();");
        Assert.True(new FileInfo(Screenshot("workspace-focal-series")).Length > 20_000);
    }

    [Fact]
    public void DotModeAndSweep_SetInThePanels_PlannedAndShown()
    {
        Resize(1440, 1000);
        OpenSample("qr-code.bmp");
        SetField("widthMm", "5");
        Driver.FindElement(By.CssSelector("#mode option[value='Dots']")).Click();
        WaitFor(d => d.FindElements(By.Id("pulsesPerDot")).Count == 1, "the dot fields shown");
        SetField("pulsesPerDot", "10");
        WaitFor(d => d.FindElement(By.Id("pulses")).Text.Contains("10 pulses per pixel", StringComparison.Ordinal), "10 pulses a pixel");
        Assert.Contains("563 dots", Text("estimate"), StringComparison.Ordinal);

        Driver.FindElement(By.CssSelector("#panel-sweep summary")).Click();
        SetField("sweepRows", "pulses-per-dot=1,5,20");
        SetField("sweepColumns", "pitch=25,50");
        WaitFor(d => d.FindElement(By.Id("sweep-summary")).Text.StartsWith("3 × 2 cells", StringComparison.Ordinal), "the sweep planned");
        Driver.ExecuteScript("document.getElementById('panel-process').scrollIntoView();");
        Assert.True(new FileInfo(Screenshot("workspace-dots")).Length > 20_000);

        // The sweep on the stage instead of the job: its own moves drawn, then the job's again.
        var jobMoves = DrawnMoves();
        Id("sweepShow").Click();
        WaitFor(_ => DrawnMoves() != jobMoves && DrawnMoves() > 0, "the sweep drawn on the stage");
        Driver.ExecuteScript("document.getElementById('panel-sweep').scrollIntoView();");
        Assert.True(new FileInfo(Screenshot("workspace-sweep")).Length > 20_000);
        Id("sweepShow").Click();
        WaitFor(_ => DrawnMoves() == jobMoves, "the job drawn again");

        Driver.FindElement(By.CssSelector("#panel-calibration summary")).Click();
        SetField("calXMeasured", "16.008");
        SetField("calYMeasured", "15.992");
        SetField("calAngle", "90.5");
        Id("calSolve").Click();
        WaitFor(d => d.FindElements(By.CssSelector("[data-solution=line]")).Count > 0, "the calibration solved");
        Driver.ExecuteScript("document.getElementById('panel-calibration').scrollIntoView();");
        Assert.True(new FileInfo(Screenshot("workspace-calibration")).Length > 20_000);

        Driver.FindElement(By.CssSelector("#panel-alignment summary")).Click();
        Driver.ExecuteScript("document.getElementById('panel-alignment').scrollIntoView();");
        Assert.True(new FileInfo(Screenshot("workspace-alignment")).Length > 20_000);
        Assert.DoesNotContain(Driver.Manage().Logs.GetLog(LogType.Browser), e => e.Level == LogLevel.Severe);
    }

    [Fact]
    public void Page_Loaded_WeighsLessThan2MB()
    {
        // The first load of a fresh profile: the page and everything it loaded, as the browser decoded it.
        var weight = Convert.ToInt64(Driver.ExecuteScript(
            """
            const all = [...performance.getEntriesByType('navigation'), ...performance.getEntriesByType('resource')];
            return all.reduce((n, e) => n + (e.decodedBodySize || 0), 0);
            """), CultureInfo.InvariantCulture);
        var files = Convert.ToInt64(Driver.ExecuteScript("return performance.getEntriesByType('resource').length + 1;"), CultureInfo.InvariantCulture);
        var readyMs = Convert.ToDouble(Driver.ExecuteScript("return performance.getEntriesByName('laserengrave-ready')[0].startTime;"), CultureInfo.InvariantCulture);
        TestContext.Current.TestOutputHelper?.WriteLine($"page weight {weight / 1024} KB in {files} files; usable {readyMs:0} ms after navigation");

        Assert.InRange(weight, 50_000, 2_000_000);
    }

    [Fact]
    public void Window_Closed_AppEnds()
    {
        var stopping = _app!.Lifetime.ApplicationStopping;
        Assert.Equal(1, _app.Services.GetRequiredService<WindowLifetime>().OpenWindows);
        Assert.False(stopping.IsCancellationRequested);

        // Leaving the page drops its connection, as closing the window does.
        Driver.Navigate().GoToUrl("about:blank");

        WaitFor(_ => stopping.IsCancellationRequested, "the app ending after its window closed");
    }

    private double[][] BoxLabels() => System.Text.Json.JsonSerializer.Deserialize<double[][]>(Id("stage-host").GetAttribute("data-box-labels") ?? "[]")!;

    private static bool Overlap(double[] a, double[] b) => a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];

    [Fact]
    public void Stage_RulerLabelsWholeAndSweepCellLabelsApart()
    {
        WaitFor(_ => View().Scale > 1, "the stage drawn");
        var canvas = Id("stage-canvas").Size;
        using var rulers = System.Text.Json.JsonDocument.Parse(Id("stage-host").GetAttribute("data-ruler-labels")!);
        var labels = rulers.RootElement.EnumerateArray().Select(l => (Axis: l[0].GetString(), Text: l[1].GetString(), Box: Enumerable.Range(2, 4).Select(i => l[i].GetDouble()).ToArray())).ToList();
        Assert.Contains(labels, l => l.Axis == "y" && l.Text == "60");
        Assert.Contains(labels, l => l.Axis == "x" && l.Text == "60");
        Assert.All(labels, l => Assert.True(l.Box[0] >= 0 && l.Box[1] >= 0 && l.Box[2] <= canvas.Width && l.Box[3] <= canvas.Height, $"{l.Axis} {l.Text} at {string.Join(", ", l.Box)} cut off the {canvas.Width} x {canvas.Height} canvas"));

        // A sweep of 1 mm cells (the default) on the stage: its cells' labels never overlap, at the fitted view or zoomed in.
        OpenSample("qr-code.bmp");
        SetField("widthMm", "5");
        Driver.FindElement(By.CssSelector("#panel-sweep summary")).Click();
        SetField("sweepRows", "speed=0.5,1,2");
        SetField("sweepColumns", "frequency=500,1000,2000");
        WaitFor(d => d.FindElement(By.Id("sweep-summary")).Text.StartsWith("3 × 3 cells", StringComparison.Ordinal), "the sweep planned");
        var jobMoves = DrawnMoves();
        Id("sweepShow").Click();
        WaitFor(_ => DrawnMoves() != jobMoves && DrawnMoves() > 0, "the sweep drawn on the stage");
        for (var zoom = 0; zoom < 6; zoom++)
        {
            var boxes = BoxLabels();
            for (var i = 0; i < boxes.Length; i++)
            {
                for (var j = i + 1; j < boxes.Length; j++)
                {
                    Assert.False(Overlap(boxes[i], boxes[j]), $"labels {i} and {j} overlap at zoom step {zoom}: {string.Join(",", boxes[i])} and {string.Join(",", boxes[j])}");
                }
            }

            var scale = View().Scale;
            Id("zoom-in").Click();
            WaitFor(_ => View().Scale > scale, "zoomed in");
        }

        Assert.True(BoxLabels().Length >= 9, $"{BoxLabels().Length} labels drawn zoomed in");
        Screenshot("sweep-labels-zoomed");
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

    [Fact]
    public void Keys_F1EscCtrlOCtrlS_HelpShownAndClosedChooserOpenedBrowserKeysPrevented()
    {
        // Whether the browser's own Ctrl+O/Ctrl+S were prevented (a window listener sees the key after the page's);
        // and the file input's click noted instead of a chooser opening, which headless Chromium cannot show.
        Driver.ExecuteScript("""
            window.__keys = [];
            window.addEventListener('keydown', (e) => window.__keys.push(e.key + (e.defaultPrevented ? ':prevented' : '')));
            document.getElementById('file').addEventListener('click', (e) => { e.preventDefault(); window.__chooser = true; });
            """);
        Driver.FindElement(By.ClassName("brand")).Click();

        new Actions(Driver).SendKeys(Keys.F1).Perform();
        WaitFor(d => d.FindElements(By.Id("help-overlay")).Count == 1, "F1: the help overlay");
        Assert.Contains("Ctrl+O", Text("help-keys"), StringComparison.Ordinal);
        Assert.Contains("Esc", Text("help-keys"), StringComparison.Ordinal);
        Screenshot("help-overlay");
        new Actions(Driver).SendKeys(Keys.Escape).Perform();
        WaitFor(d => d.FindElements(By.Id("help-overlay")).Count == 0, "Esc: the help overlay closed");

        // F1 and Esc act in a field too.
        Id("widthMm").Click();
        new Actions(Driver).SendKeys(Keys.F1).Perform();
        WaitFor(d => d.FindElements(By.Id("help-overlay")).Count == 1, "F1 in a field: the help overlay");
        new Actions(Driver).SendKeys(Keys.Escape).Perform();
        WaitFor(d => d.FindElements(By.Id("help-overlay")).Count == 0, "Esc in a field: the help overlay closed");

        Driver.FindElement(By.ClassName("brand")).Click();
        new Actions(Driver).KeyDown(Keys.Control).SendKeys("o").KeyUp(Keys.Control).Perform();
        WaitFor(d => ((IJavaScriptExecutor)d).ExecuteScript("return window.__chooser === true;") is true, "Ctrl+O: the file chooser");
        new Actions(Driver).KeyDown(Keys.Control).SendKeys("s").KeyUp(Keys.Control).Perform();
        WaitFor(d => d.FindElements(By.Id("layers-file-error")).Count == 1, "Ctrl+S: the layers panel says why nothing was saved");
        var keys = ((IEnumerable<object>)Driver.ExecuteScript("return window.__keys;")!).Select(k => k.ToString()).ToArray();
        Assert.Contains("F1:prevented", keys);
        Assert.Contains("o:prevented", keys);
        Assert.Contains("s:prevented", keys);
    }

    [Fact]
    public void Stage_JobDraggedOffTheTravel_Refused()
    {
        OpenSample("qr-code.bmp");
        SetField("widthMm", "5");
        WaitFor(d => d.FindElement(By.Id("status-estimate")).Text.StartsWith("5 × 5 mm", StringComparison.Ordinal), "5 mm job planned");
        WaitFor(_ => View().Scale > 1, "the stage drawn");
        var (scale, ox, oy) = View();
        var canvas = Id("stage-canvas");

        new Actions(Driver)
            .MoveToLocation((int)(canvas.Location.X + ox + (3 * scale)), (int)(canvas.Location.Y + oy + (3 * scale)))
            .ClickAndHold().MoveByOffset((int)(-5 * scale), 0).Release().Perform();

        WaitFor(d => d.FindElements(By.Id("drop-refused")).Count == 1, "the drop refused");
        Assert.Contains("travel", Text("drop-refused"), StringComparison.Ordinal);
        Assert.Equal(1, FieldValue("originXMm"));
    }
}
