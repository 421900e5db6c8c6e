using LaserEngrave.App.Web;
using Microsoft.AspNetCore.Builder;
using Microsoft.AspNetCore.Hosting.Server;
using Microsoft.AspNetCore.Hosting.Server.Features;
using Microsoft.Extensions.DependencyInjection;
using OpenQA.Selenium;
using OpenQA.Selenium.Chrome;

namespace LaserEngrave.App.Tests.Web;

/// <summary>The real page in headless Chromium against the app on a real port, the simulator in virtual time.</summary>
public sealed class BrowserTests : IAsyncLifetime
{
    private const string ChromiumPath = "/usr/bin/chromium";
    private const string DriverFolder = "/usr/bin";

    private readonly TestFiles.TempFolder _folder = TestFiles.NewFolder();
    private readonly TestFiles.TempFolder _profile = TestFiles.NewFolder();
    private WebApplication? _app;
    private ChromeDriver? _driver;
    private string _url = string.Empty;

    private ChromeDriver Driver => _driver ?? throw new InvalidOperationException("not started");

    /// <summary>Screenshots land here (the test output folder), one PNG per view.</summary>
    public static string ScreenshotFolder => Path.Combine(AppContext.BaseDirectory, "screenshots");

    public async ValueTask InitializeAsync()
    {
        _app = AppHost.Build([], "http://127.0.0.1:0", services => AppFactory.UseTestServices(services, _folder.Path));
        await _app.StartAsync(TestContext.Current.CancellationToken);
        _url = _app.Services.GetRequiredService<IServer>().Features.Get<IServerAddressesFeature>()!.Addresses.First();

        var options = new ChromeOptions { BinaryLocation = ChromiumPath };
        options.AddArguments(
            "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking",
            "--disable-component-update", "--disable-sync", "--disable-dev-shm-usage", "--window-size=1400,1000", "--user-data-dir=" + _profile.Path);
        var service = ChromeDriverService.CreateDefaultService(DriverFolder, "chromedriver");
        service.HideCommandPromptWindow = true;
        service.SuppressInitialDiagnosticInformation = true;
        _driver = new ChromeDriver(service, options, TimeSpan.FromSeconds(60));
        // The address the app prints: the page's first load shows the start's token and keeps it as a cookie.
        _driver.Navigate().GoToUrl($"{_url}/?{AccessToken.QueryName}={_app.Services.GetRequiredService<AccessToken>().Value}");
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

    private IWebElement Id(string id) => Driver.FindElement(By.Id(id));

    /// <summary>
    /// Presses Start until the run is under way: right after "connected" shows, the connect may still hold the machine
    /// (it reads the devices' state), and the interlock refuses a Start until it ends. A press during the run is ignored.
    /// </summary>
    private void StartRun() => WaitFor(() =>
    {
        if (Id("status-run").Text is "idle")
        {
            Id("start").Click();
        }

        return Id("status-run").Text is not "idle";
    }, "the run started", 60);

    private void WaitFor(Func<bool> condition, string what, double seconds = 30)
    {
        var end = DateTime.UtcNow + TimeSpan.FromSeconds(seconds);
        while (!condition())
        {
            Assert.True(DateTime.UtcNow < end, $"timed out waiting for: {what}");
            Thread.Sleep(100);
        }
    }

    private void Upload(string path)
    {
        var input = Id("file");
        Driver.ExecuteScript("arguments[0].hidden = false;", input);
        input.SendKeys(path);
        Driver.ExecuteScript("arguments[0].hidden = true;", input);
    }

    private void Show(string view)
    {
        Driver.FindElement(By.CssSelector($"#nav button[data-view='{view}']")).Click();
        WaitFor(() => Id("view-" + view).Displayed, view + " view shown");
    }

    private void SetField(string id, string value)
    {
        var input = Id(id);
        input.Clear();
        input.SendKeys(value + Keys.Tab);
    }

    private string Screenshot(string name)
    {
        Directory.CreateDirectory(ScreenshotFolder);
        var path = Path.Combine(ScreenshotFolder, name + ".png");
        Driver.GetScreenshot().SaveAsFile(path);
        return path;
    }

    [Fact]
    public void Page_LoadImage_MaskAndEstimateShown()
    {
        Upload(TestFiles.Asset("qr-code.bmp"));

        WaitFor(() => Id("status-estimate").Text.Contains("est.", StringComparison.Ordinal), "estimate in the top bar");
        WaitFor(() => (bool)Driver.ExecuteScript("const i = document.getElementById('img-mask'); return i.complete && i.naturalWidth === 41;")!, "mask picture loaded");
        Assert.Contains("41 × 41", Id("image-meta").Text, StringComparison.Ordinal);
        Screenshot("image");
    }

    [Fact]
    public void Page_NoImageYet_HintShownAndASampleOpens()
    {
        WaitFor(() => Driver.FindElements(By.CssSelector("#recent optgroup[label='Samples'] option")).Count == 3, "three samples offered");
        Assert.True(Id("no-image").Displayed);
        Assert.False(Id("image-pair").Displayed);

        Driver.ExecuteScript("const s = document.getElementById('recent'); s.value = [...s.options].find((o) => o.text === 'text-banner.png').value;");
        Id("open-recent").Click();

        WaitFor(() => Id("image-pair").Displayed, "original and mask shown");
        Assert.False(Id("no-image").Displayed);
        Assert.Contains("308 × 60", Id("image-meta").Text, StringComparison.Ordinal);
        Screenshot("image-sample");
    }

    [Fact]
    public void Page_SizeChange_EstimateUpdates()
    {
        Upload(TestFiles.Asset("qr-code.bmp"));
        WaitFor(() => Id("status-estimate").Text.Contains("est.", StringComparison.Ordinal), "estimate in the top bar");
        Show("size");
        var before = Id("status-estimate").Text;

        SetField("widthMm", "12");

        WaitFor(() => Id("status-estimate").Text != before, "estimate changed");
        Assert.Contains("12 × 12 mm", Id("status-estimate").Text, StringComparison.Ordinal);
        Assert.Equal("12", Id("heightMm").GetAttribute("value"));
        Screenshot("size");
    }

    [Fact]
    public void Page_OriginOffTravel_WarningBesideOrigin()
    {
        Upload(TestFiles.Asset("qr-code.bmp"));
        WaitFor(() => Id("status-estimate").Text.Contains("est.", StringComparison.Ordinal), "estimate in the top bar");
        Show("size");

        SetField("originXMm", "58");

        var warning = Driver.FindElement(By.CssSelector("[data-warning='origin']"));
        WaitFor(() => warning.Text.Contains("travel", StringComparison.Ordinal), "warning beside the origin");
    }

    [Fact]
    public void Page_SimulatedRun_CompletesAndShowsBurnedPreview()
    {
        Upload(TestFiles.WriteChecker(_folder.Path, 12, 8));
        WaitFor(() => Id("status-estimate").Text.Contains("est.", StringComparison.Ordinal), "estimate in the top bar");
        Show("size");
        SetField("widthMm", "1.2");
        Show("machine");
        Id("connect").Click();
        WaitFor(() => Id("status-machine").Text.Contains("simulator", StringComparison.Ordinal), "connected to the simulator");
        Show("log");
        Id("sampleId").SendKeys("B-1");
        Show("preview");

        StartRun();

        WaitFor(() => Id("status-run").Text == "completed", "run completed", 120);
        WaitFor(() => Id("progress-text").Text == "100 %", "progress at 100 %");
        var burnedPixels = Convert.ToInt64(Driver.ExecuteScript(
            """
            const c = document.getElementById('plan-canvas');
            const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
            let n = 0;
            for (let i = 0; i < d.length; i += 4) if (d[i] > 200 && d[i + 1] < 60 && d[i + 2] > 50 && d[i + 2] < 110) n++;
            return n;
            """), System.Globalization.CultureInfo.InvariantCulture);
        Assert.True(burnedPixels > 100, $"only {burnedPixels} pixels drawn in the burned colour");
        var screenshot = Screenshot("preview-after-run");
        Assert.True(new FileInfo(screenshot).Length > 10_000);
        Show("log");
        WaitFor(() => Id("last-run").Text.Contains("B-1", StringComparison.Ordinal), "sample ID in the last run's summary");
        Screenshot("log");
    }

    [Fact]
    public void Page_EachView_Screenshot()
    {
        Upload(TestFiles.Asset("text-banner.png"));
        WaitFor(() => Id("status-estimate").Text.Contains("est.", StringComparison.Ordinal), "estimate in the top bar");
        Show("size");
        SetField("widthMm", "20");
        WaitFor(() => Id("status-estimate").Text.Contains("20 ×", StringComparison.Ordinal), "width applied");
        Screenshot("size");
        Show("process");
        SetField("overscanMm", "0.5");
        WaitFor(() => Id("estimate").Text.Contains("Burn runs", StringComparison.Ordinal), "estimate figures");
        Screenshot("process");
        Show("machine");
        Id("connect").Click();
        WaitFor(() => Id("machine-state").Text.Contains("firmware", StringComparison.Ordinal), "identity read");
        Screenshot("machine");
        Show("moves");
        // Pressed again while the connect still holds the machine (refused) or the move runs (refused): harmless.
        WaitFor(() =>
        {
            if (Id("moves-position").Text.Contains("10.0787", StringComparison.Ordinal) || Id("moves-position").Text.Contains("1 mm", StringComparison.Ordinal))
            {
                return true;
            }

            Id("goto-origin").Click();
            return false;
        }, "at the origin", 60);
        Screenshot("test-moves");
        Show("preview");
        WaitFor(() => (bool)Driver.ExecuteScript("return plan.data !== null && planCanvas !== null;")!, "plan drawn");
        Screenshot("preview");
        Id("theme-toggle").Click();
        WaitFor(() => (string)Driver.ExecuteScript("return document.documentElement.dataset.theme;")! == "dark", "dark theme");
        Thread.Sleep(300);
        Screenshot("preview-dark");
        Show("image");
        Screenshot("image-dark");
    }

    [Fact]
    public void Page_RunPausedMidway_LiveProgressThenResumesToCompletion()
    {
        Upload(TestFiles.Asset("qr-code.bmp"));
        WaitFor(() => Id("status-estimate").Text.Contains("est.", StringComparison.Ordinal), "estimate in the top bar");
        Show("size");
        SetField("widthMm", "4");
        Show("machine");
        Id("connect").Click();
        WaitFor(() => Id("status-machine").Text.Contains("simulator", StringComparison.Ordinal), "connected to the simulator");
        Show("preview");
        StartRun();
        WaitFor(() => double.Parse(Id("progress-text").Text.TrimEnd('%', ' '), System.Globalization.CultureInfo.InvariantCulture) >= 20, "a fifth done", 120);

        Id("pause").Click();

        WaitFor(() => Id("status-run").Text.StartsWith("paused", StringComparison.Ordinal), "paused");
        Thread.Sleep(500);
        Assert.Contains("row ", Id("progress-figures").Text, StringComparison.Ordinal);
        Assert.True(Id("resume").Enabled && Id("abort").Enabled && !Id("start").Enabled);
        Screenshot("preview-paused");
        Id("resume").Click();
        WaitFor(() => Id("status-run").Text == "completed", "run completed", 180);
    }
}
