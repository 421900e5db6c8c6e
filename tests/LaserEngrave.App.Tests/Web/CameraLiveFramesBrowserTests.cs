using LaserEngrave.App.Services;
using LaserEngrave.App.Tests.Components;
using LaserEngrave.App.ViewModels;
using LaserEngrave.App.Web;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator;
using Microsoft.AspNetCore.Builder;
using Microsoft.AspNetCore.Hosting.Server;
using Microsoft.AspNetCore.Hosting.Server.Features;
using Microsoft.Extensions.DependencyInjection;
using OpenQA.Selenium;
using OpenQA.Selenium.Chrome;
using OpenQA.Selenium.Support.UI;

namespace LaserEngrave.App.Tests.Web;

/// <summary>
/// A live camera's frames from the page to the app in Chromium: the fake capture device plays a blank y4m this test writes,
/// the simulator is taken for a real machine (its twin hidden), and Calibrate asks the page for frames, which the app
/// measures and refuses with its plain sentence (issue 37).
/// </summary>
public sealed class CameraLiveFramesBrowserTests : IAsyncLifetime
{
    private const int Width = 320;
    private const int Height = 240;
    private readonly TestFiles.TempFolder _folder = TestFiles.NewFolder();
    private readonly TestFiles.TempFolder _profile = TestFiles.NewFolder();
    private WebApplication? _app;
    private ChromeDriver? _driver;

    public async ValueTask InitializeAsync()
    {
        var video = Path.Combine(_folder.Path, "blank.y4m");
        await WriteBlankY4mAsync(video);
        _app = AppHost.Build([], "http://127.0.0.1:0", services =>
        {
            AppFactory.UseTestServices(services, _folder.Path);
            services.AddSingleton<IMachineConnectionFactory>(new HiddenTwinFactory());
        });
        await _app.StartAsync(TestContext.Current.CancellationToken);
        var profile = MachineProfile.Default with { Camera = new CameraProfile { WidthPx = Width, HeightPx = Height, UmPerPixel = 2 } };
        var profilePath = Path.Combine(_folder.Path, "camera-profile.json");
        profile.Save(profilePath);
        _app.Services.GetRequiredService<MainViewModel>().UseProfile(profilePath, profile);
        _app.Services.GetRequiredService<CameraViewModel>().Refresh();

        var options = new ChromeOptions { BinaryLocation = "/usr/bin/chromium" };
        options.AddArguments(
            "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking", "--disable-dev-shm-usage",
            "--window-size=1366,768", "--user-data-dir=" + _profile.Path,
            "--use-fake-ui-for-media-stream", "--use-fake-device-for-media-stream", "--use-file-for-fake-video-capture=" + video);
        var service = ChromeDriverService.CreateDefaultService("/usr/bin", "chromedriver");
        service.SuppressInitialDiagnosticInformation = true;
        _driver = new ChromeDriver(service, options, TimeSpan.FromSeconds(60));
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

        _folder.Dispose();
        _profile.Dispose();
    }

    [Fact]
    public void Calibrate_BlankLiveCamera_FramesReachTheAppWhichRefusesForTooLittleTexture()
    {
        var driver = _driver!;
        var url = _app!.Services.GetRequiredService<IServer>().Features.Get<IServerAddressesFeature>()!.Addresses.First().TrimEnd('/');
        driver.Navigate().GoToUrl($"{url}/#{LaunchCodes.FragmentName}={_app.Services.GetRequiredService<LaunchCodes>().Issue()}");
        driver.ExecuteCdpCommand("Emulation.setDeviceMetricsOverride", new Dictionary<string, object?>
        {
            ["width"] = 1366, ["height"] = 768, ["deviceScaleFactor"] = 1, ["mobile"] = false,
        });
        var wait = new WebDriverWait(driver, TimeSpan.FromSeconds(60)) { PollingInterval = TimeSpan.FromMilliseconds(50) };
        wait.IgnoreExceptionTypes(typeof(NoSuchElementException), typeof(StaleElementReferenceException));
        wait.Until(d => d.FindElement(By.Id("app")).GetAttribute("data-interactive") == "true");
        driver.FindElement(By.Id("connect")).Click();
        wait.Until(d => d.FindElement(By.Id("machine-connection")).Text.Contains("simulator", StringComparison.Ordinal));
        driver.ExecuteScript("document.getElementById('panel-camera').open = true; document.getElementById('panel-camera').scrollIntoView();");
        wait.Until(d => d.FindElement(By.Id("camera-source")).Text.Contains($"({Width} x {Height})", StringComparison.Ordinal));
        wait.Until(d => d.FindElement(By.Id("camera-calibrate")).GetAttribute("disabled") is null);

        driver.FindElement(By.Id("camera-calibrate")).Click();

        wait.Until(d => d.FindElements(By.CssSelector("[data-error=camera]")).Count > 0);
        Assert.StartsWith("the image has too little texture to track", driver.FindElement(By.CssSelector("[data-error=camera]")).Text, StringComparison.Ordinal);
        // The frame came from the page through the stream, at the size asked, and was measured here.
        Assert.Equal($"Frames measured here: 1 ({Width} x {Height} grey)", driver.FindElement(By.Id("camera-live-frames")).Text);
        Assert.Equal(1, _app.Services.GetRequiredService<CameraViewModel>().LiveFramesReceived);
        driver.ExecuteScript("document.querySelector('[data-error=camera]').scrollIntoView({ block: 'end' });");
        Directory.CreateDirectory(BrowserTest.ScreenshotFolder);
        driver.GetScreenshot().SaveAsFile(Path.Combine(BrowserTest.ScreenshotFolder, "camera-live-blank.png"));
    }

    // A grey card in front of the camera: luma 126 and 127 in a fine check, nothing to track.
    private static async Task WriteBlankY4mAsync(string path)
    {
        await using var file = File.Create(path);
        file.Write(System.Text.Encoding.ASCII.GetBytes($"YUV4MPEG2 W{Width} H{Height} F5:1 Ip A1:1 C420\n"));
        var luma = Enumerable.Range(0, Width * Height).Select(i => (byte)(126 + ((i + (i / Width)) % 2))).ToArray();
        var chroma = Enumerable.Repeat((byte)128, Width * Height / 2).ToArray();
        for (var i = 0; i < 2; i++)
        {
            file.Write("FRAME\n"u8);
            file.Write(luma);
            file.Write(chroma);
        }
    }

    // The simulator with its twin hidden: the app takes it for a real machine, so the camera's frames come from the page.
    private sealed class HiddenTwinFactory : IMachineConnectionFactory
    {
        private readonly MachineConnectionFactory _inner = new(new SimulatorOptions());

        public async Task<IMachineConnection> ConnectAsync(MachineChoice choice, MachineProfile profile, CancellationToken cancellationToken) =>
            new NotATwin(await _inner.ConnectAsync(choice, profile, cancellationToken));

        public IReadOnlyList<string> ListPorts() => [];
    }
}
