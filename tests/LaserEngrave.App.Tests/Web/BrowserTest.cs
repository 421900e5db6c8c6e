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

/// <summary>What every browser test stands on: the workspace in headless Chromium against the app on a real port, the simulator in virtual time.</summary>
/// <remarks>No sleeps: every step waits for a condition the page shows. Each test has its own app; the class's tests share one Chromium (<see cref="SharedBrowser"/>).</remarks>
public abstract class BrowserTest : IAsyncLifetime, IClassFixture<SharedBrowser>
{
    private readonly TestFiles.TempFolder _folder = TestFiles.NewFolder();
    private WebApplication? _app;
    private SharedBrowser? _browser;
    private ChromeDriver? _driver;
    private string _url = string.Empty;
    private string _token = string.Empty;

    protected ChromeDriver Driver => _driver ?? throw new InvalidOperationException("not started");

    /// <summary>The app under test, on its own port.</summary>
    protected WebApplication Host => _app ?? throw new InvalidOperationException("not started");

    /// <summary>The app's address and its start's token.</summary>
    protected string Url => _url;

    protected string Secret => _token;

    /// <summary>The launch address <see cref="Open"/> last used (its code is used up once the page has loaded).</summary>
    protected string LaunchAddress { get; private set; } = string.Empty;

    /// <summary>The app's data folder (settings, images, logs).</summary>
    protected string DataFolder => _folder.Path;

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
            services.AddSingleton(new WindowLifetimeOptions(TestContext.Current.TestMethod?.MethodName == "Window_Closed_AppEnds" ? IdleExit : null));
            AddServices(services);
        });
        await _app.StartAsync(TestContext.Current.CancellationToken);
        _url = _app.Services.GetRequiredService<IServer>().Features.Get<IServerAddressesFeature>()!.Addresses.First();
        _token = _app.Services.GetRequiredService<AccessToken>().Value;

        _browser = await TestContext.Current.GetFixture<SharedBrowser>() ?? throw new InvalidOperationException("no browser: the class fixture is missing");
        _driver = _browser.Fresh();
        Open();
    }

    /// <summary>Services a test class replaces besides the test ones (e.g. the simulator at the machine's pace).</summary>
    protected virtual void AddServices(IServiceCollection services)
    {
    }

    public async ValueTask DisposeAsync()
    {
        _browser?.Leave(_url.TrimEnd('/'));
        if (_app is not null)
        {
            await _app.StopAsync(CancellationToken.None);
            await _app.DisposeAsync();
        }

        _folder.Dispose();
    }

    /// <summary>Opens the page as its window does: at an address with a new one-time launch code, which the page trades for the token.</summary>
    protected void Open()
    {
        LaunchAddress = $"{_url.TrimEnd('/')}/#{LaunchCodes.FragmentName}={Host.Services.GetRequiredService<LaunchCodes>().Issue()}";
        Driver.Navigate().GoToUrl(LaunchAddress);
        WaitFor(d => d.FindElement(By.Id("app")).GetAttribute("data-interactive") == "true", "the page is interactive");
        WaitFor(d => d.FindElement(By.Id("stage-host")).GetAttribute("data-ready") == "true", "the stage canvas is ready");
    }

    protected IWebElement Id(string id) => Driver.FindElement(By.Id(id));

    private static readonly TimeSpan PollInterval = TimeSpan.FromMilliseconds(50);

    protected void WaitFor(Func<IWebDriver, bool> condition, string what, double seconds = 30)
    {
        // Polled every 50 ms, not Selenium's default 500: a condition met just after a poll no longer costs half a second.
        var wait = new WebDriverWait(Driver, TimeSpan.FromSeconds(seconds)) { Message = "waiting for: " + what, PollingInterval = PollInterval };
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

    protected string Text(string id) => Id(id).Text;

    protected void SetField(string id, string value)
    {
        var input = Id(id);
        input.Clear();
        input.SendKeys(value + Keys.Tab);
    }

    protected void OpenSample(string name)
    {
        WaitFor(d => d.FindElements(By.CssSelector($"#samples button[data-path$='{name}']")).Count == 1, name + " offered");
        Driver.FindElement(By.CssSelector($"#samples button[data-path$='{name}']")).Click();
        WaitFor(d => d.FindElement(By.Id("image-meta")).Text.Contains(name, StringComparison.Ordinal), name + " open");
    }

    protected bool Enabled(string id) => Id(id).GetAttribute("disabled") is null;

    protected double Progress() => double.Parse(Text("progress-text").TrimEnd('%', ' '), CultureInfo.InvariantCulture);

    protected string Screenshot(string name)
    {
        Directory.CreateDirectory(ScreenshotFolder);
        var path = Path.Combine(ScreenshotFolder, name + ".png");
        Driver.GetScreenshot().SaveAsFile(path);
        return path;
    }

    protected long HorizontalOverflow() => Convert.ToInt64(
        Driver.ExecuteScript("return document.documentElement.scrollWidth - document.documentElement.clientWidth;"), CultureInfo.InvariantCulture);

    protected void Resize(int width, int height)
    {
        Driver.Manage().Window.Size = new System.Drawing.Size(width, height);
        WaitFor(d => Convert.ToInt64(((IJavaScriptExecutor)d).ExecuteScript("return window.innerWidth;"), CultureInfo.InvariantCulture) <= width, $"window {width} wide");
    }

    /// <summary>The stage's view (px per mm, offset) as the canvas last drew it.</summary>
    protected (double Scale, double X, double Y) View()
    {
        var parts = Id("stage-host").GetAttribute("data-view")!.Split(',').Select(p => double.Parse(p, CultureInfo.InvariantCulture)).ToArray();
        return (parts[0], parts[1], parts[2]);
    }

    /// <summary>The laser's position as the jog pad shows it, mm.</summary>
    protected (double? X, double? Y) Position()
    {
        var parts = Text("position").Replace("mm", "", StringComparison.Ordinal).Split(['X', 'Y', '·'], StringSplitOptions.RemoveEmptyEntries | StringSplitOptions.TrimEntries);
        static double? Number(string text) => double.TryParse(text, NumberStyles.Float, CultureInfo.InvariantCulture, out var v) ? v : null;
        return parts.Length == 2 ? (Number(parts[0]), Number(parts[1])) : (null, null);
    }

    protected double FieldValue(string id) => double.Parse(Id(id).GetDomProperty("value")!, CultureInfo.InvariantCulture);

    /// <summary>The page's own area at exactly 1280 x 720, as docs/user-guide.md shows it.</summary>
    protected void Size1280x720() => PageSize(1280, 720);

    /// <summary>The page's own area at exactly <paramref name="width"/> x <paramref name="height"/> (a window's is larger by its frame).</summary>
    protected void PageSize(int width, int height)
    {
        Driver.ExecuteCdpCommand("Emulation.setDeviceMetricsOverride", new Dictionary<string, object?>
        {
            ["width"] = width, ["height"] = height, ["deviceScaleFactor"] = 1, ["mobile"] = false,
        });
        WaitFor(d => Convert.ToInt64(((IJavaScriptExecutor)d).ExecuteScript("return window.innerHeight;"), CultureInfo.InvariantCulture) == height, $"a {width} x {height} page");
    }

    /// <summary>Zooms the stage in with the wheel around (<paramref name="xMm"/>, <paramref name="yMm"/>), to show a small job.</summary>
    protected void ZoomAround(double xMm, double yMm, int steps)
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

    protected int DrawnMoves() => int.Parse(Driver.FindElement(By.Id("stage-host")).GetAttribute("data-drawn-moves") ?? "0", CultureInfo.InvariantCulture);

    /// <summary>Waits until the theme's colour transitions have ended (endless animations, a busy spinner, do not count).</summary>
    protected void ColoursSettled() => WaitFor(
        d => Convert.ToInt64(((IJavaScriptExecutor)d).ExecuteScript(
            "return document.getAnimations().filter(a => a.effect && a.effect.getTiming().iterations !== Infinity).length;"), CultureInfo.InvariantCulture) == 0,
        "colours settled");

    /// <summary>The contrast ratio (WCAG) of an element's text against the first opaque background behind it.</summary>
    protected double Contrast(string selector) => Convert.ToDouble(Driver.ExecuteScript(
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

    protected double[][] BoxLabels() => System.Text.Json.JsonSerializer.Deserialize<double[][]>(Id("stage-host").GetAttribute("data-box-labels") ?? "[]")!;

    protected static bool Overlap(double[] a, double[] b) => a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
}
