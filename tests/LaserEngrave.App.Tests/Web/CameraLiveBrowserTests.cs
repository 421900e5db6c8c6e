using System.Globalization;
using LaserEngrave.App.ViewModels;
using LaserEngrave.App.Web;
using LaserEngrave.Core.Camera;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Camera;
using Microsoft.AspNetCore.Builder;
using Microsoft.AspNetCore.Hosting.Server;
using Microsoft.AspNetCore.Hosting.Server.Features;
using Microsoft.Extensions.DependencyInjection;
using OpenQA.Selenium;
using OpenQA.Selenium.Chrome;
using OpenQA.Selenium.Support.UI;

namespace LaserEngrave.App.Tests.Web;

/// <summary>
/// The Camera panel with a camera in the page: Chromium's fake capture device plays a y4m file this test writes (frames
/// of the twin's camera), through getUserMedia as any camera would (issue 37). Its own Chromium: the fake device is a
/// start flag.
/// </summary>
public sealed class CameraLiveBrowserTests : IAsyncLifetime
{
    private const int Width = 320;
    private const int Height = 240;
    private readonly TestFiles.TempFolder _folder = TestFiles.NewFolder();
    private readonly TestFiles.TempFolder _profile = TestFiles.NewFolder();
    private WebApplication? _app;
    private ChromeDriver? _driver;
    private CameraFrame? _frame;

    public async ValueTask InitializeAsync()
    {
        var video = Path.Combine(_folder.Path, "camera.y4m");
        _frame = await WriteY4mAsync(video);
        _app = AppHost.Build([], "http://127.0.0.1:0", services => AppFactory.UseTestServices(services, _folder.Path));
        await _app.StartAsync(TestContext.Current.CancellationToken);
        var profile = MachineProfile.Default with { Camera = new CameraProfile { WidthPx = Width, HeightPx = Height, UmPerPixel = 2 } };
        var profilePath = Path.Combine(_folder.Path, "camera-profile.json");
        profile.Save(profilePath);
        _app.Services.GetRequiredService<MainViewModel>().UseProfile(profilePath, profile);
        _app.Services.GetRequiredService<CameraViewModel>().Refresh();

        var options = new ChromeOptions { BinaryLocation = "/usr/bin/chromium" };
        options.AddArguments(
            "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking", "--disable-dev-shm-usage",
            "--window-size=1280,900", "--user-data-dir=" + _profile.Path,
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
    public void CameraPanel_FakeCaptureDevice_ShowsTheLiveImageWithItsSharpness()
    {
        var driver = _driver!;
        var url = _app!.Services.GetRequiredService<IServer>().Features.Get<IServerAddressesFeature>()!.Addresses.First().TrimEnd('/');
        // As the app's window opens it: a one-time launch code the page trades for the token (a token in the address is refused).
        driver.Navigate().GoToUrl($"{url}/#{LaunchCodes.FragmentName}={_app.Services.GetRequiredService<LaunchCodes>().Issue()}");
        var wait = new WebDriverWait(driver, TimeSpan.FromSeconds(60)) { PollingInterval = TimeSpan.FromMilliseconds(50) };
        wait.IgnoreExceptionTypes(typeof(NoSuchElementException), typeof(StaleElementReferenceException));
        wait.Until(d => d.FindElement(By.Id("app")).GetAttribute("data-interactive") == "true");
        driver.ExecuteScript("document.getElementById('panel-camera').open = true; document.getElementById('panel-camera').scrollIntoView();");

        wait.Until(d => d.FindElement(By.Id("camera-source")).Text.Contains($"({Width} x {Height})", StringComparison.Ordinal));
        wait.Until(d => d.FindElement(By.Id("camera-sharpness")).Text != "—");
        var pageSharpness = double.Parse(driver.FindElement(By.Id("camera-sharpness")).Text, CultureInfo.InvariantCulture);
        var playing = driver.ExecuteScript("const v = document.getElementById('camera-video'); return !v.paused && v.videoWidth === 320;") is true;

        // The page measures the frame the browser decoded (YUV to RGB and back to grey): the same figure within a fifth.
        var expected = FocusMeasure.Sharpness(_frame!);
        Assert.True(playing, "the video does not play");
        Assert.InRange(pageSharpness, expected * 0.8, expected * 1.2);
        Assert.Contains("Live: ", driver.FindElement(By.Id("camera-source")).Text, StringComparison.Ordinal);
        Assert.Empty(driver.FindElements(By.CssSelector("[data-error=camera]")));
        Directory.CreateDirectory(BrowserTest.ScreenshotFolder);
        driver.GetScreenshot().SaveAsFile(Path.Combine(BrowserTest.ScreenshotFolder, "camera-live.png"));
    }

    // Two frames of the twin's camera as 4:2:0 video, grey (chroma 128): Chromium loops the file.
    private static async Task<CameraFrame> WriteY4mAsync(string path)
    {
        var profile = MachineProfile.Default with { Camera = new CameraProfile { WidthPx = Width, HeightPx = Height, UmPerPixel = 2 } };
        await using var machine = SimulatedMachine.CreateInProcess(profile);
        var camera = new TwinCamera(machine);
        camera.AddMark(20_000, 20_000, 40);
        var frame = camera.Render(20_000, 20_000, 0, 1);
        await using var file = File.Create(path);
        // Video levels: the browser decodes luma 16..235 as black..white, so the page sees the twin's grey levels again.
        var header = System.Text.Encoding.ASCII.GetBytes($"YUV4MPEG2 W{Width} H{Height} F5:1 Ip A1:1 C420\n");
        var luma = frame.Pixels.Select(v => (byte)Math.Round(16 + (v * 219.0 / 255))).ToArray();
        file.Write(header);
        var chroma = Enumerable.Repeat((byte)128, Width * Height / 2).ToArray();
        for (var i = 0; i < 2; i++)
        {
            file.Write("FRAME\n"u8);
            file.Write(luma);
            file.Write(chroma);
        }

        return frame;
    }
}
