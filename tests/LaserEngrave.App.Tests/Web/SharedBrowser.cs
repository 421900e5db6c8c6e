using OpenQA.Selenium;
using OpenQA.Selenium.Chrome;

namespace LaserEngrave.App.Tests.Web;

/// <summary>
/// One headless Chromium for all the tests of a browser test class (an xunit class fixture), each test on a fresh tab
/// with its own app: starting Chromium with a fresh profile for every test cost about 3 s of CPU a test, most of the
/// browser tests' time.
/// </summary>
/// <remarks>
/// Nothing of one test reaches the next: <see cref="Leave"/> clears what the app's page stored; <see cref="Fresh"/>
/// leaves one new tab (with its own sessionStorage), no cookies, no cache, the window at its first size with no
/// emulated size, no key held and an empty console log. A browser that fails at that is replaced by a new one.
/// </remarks>
public sealed class SharedBrowser : IDisposable
{
    private const string ChromiumPath = "/usr/bin/chromium";
    private const string DriverFolder = "/usr/bin";

    private readonly TestFiles.TempFolder _profile = TestFiles.NewFolder();
    private ChromeDriver? _driver;
    private System.Drawing.Size _firstSize;

    /// <summary>The browser as a test should find it, started at the first test and put back to that state for the others.</summary>
    public ChromeDriver Fresh()
    {
        if (_driver is not null)
        {
            try
            {
                Reset(_driver);
                return _driver;
            }
            catch (WebDriverException)
            {
                Quit();
            }
        }

        _driver = Start();
        _firstSize = _driver.Manage().Window.Size;
        return _driver;
    }

    /// <summary>
    /// Leaves the test's page (its connection to the app closes, as when its window closes) before the app stops, and
    /// forgets what the page stored for the app's <paramref name="origin"/>, should a later app get the same port.
    /// </summary>
    public void Leave(string origin)
    {
        try
        {
            _driver?.Navigate().GoToUrl("about:blank");
            _driver?.ExecuteCdpCommand("Storage.clearDataForOrigin", new Dictionary<string, object?> { ["origin"] = origin, ["storageTypes"] = "all" });
        }
        catch (WebDriverException)
        {
            Quit();
        }
    }

    public void Dispose()
    {
        Quit();
        _profile.Dispose();
    }

    private ChromeDriver Start()
    {
        var options = new ChromeOptions { BinaryLocation = ChromiumPath };
        options.AddArguments(
            "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking",
            "--disable-component-update", "--disable-sync", "--disable-dev-shm-usage", "--window-size=1280,720", "--user-data-dir=" + _profile.Path);
        options.SetLoggingPreference(LogType.Browser, LogLevel.Severe);
        var service = ChromeDriverService.CreateDefaultService(DriverFolder, "chromedriver");
        service.HideCommandPromptWindow = true;
        service.SuppressInitialDiagnosticInformation = true;
        return new ChromeDriver(service, options, TimeSpan.FromSeconds(60));
    }

    private void Reset(ChromeDriver driver)
    {
        driver.ResetInputState();

        // A new tab, the others closed: no page, window or sessionStorage of the last test is left.
        var old = driver.WindowHandles;
        driver.SwitchTo().NewWindow(WindowType.Tab);
        var tab = driver.CurrentWindowHandle;
        foreach (var handle in old)
        {
            driver.SwitchTo().Window(handle).Close();
        }

        driver.SwitchTo().Window(tab);
        driver.ExecuteCdpCommand("Emulation.clearDeviceMetricsOverride", new());
        driver.ExecuteCdpCommand("Network.clearBrowserCookies", new());
        driver.ExecuteCdpCommand("Network.clearBrowserCache", new());
        driver.Manage().Window.Size = _firstSize;
        driver.Manage().Logs.GetLog(LogType.Browser);
    }

    private void Quit()
    {
        try
        {
            _driver?.Quit();
        }
        catch (WebDriverException)
        {
            // Already gone: a new one is started.
        }

        _driver?.Dispose();
        _driver = null;
    }
}
