using LaserEngrave.App.ViewModels;
using LaserEngrave.App.Web;
using LaserEngrave.Core.Geometry;
using Microsoft.AspNetCore.Builder;
using Microsoft.AspNetCore.Hosting.Server;
using Microsoft.AspNetCore.Hosting.Server.Features;
using Microsoft.Extensions.DependencyInjection;
using OpenQA.Selenium;
using OpenQA.Selenium.Chrome;
using OpenQA.Selenium.Support.UI;

namespace LaserEngrave.App.Tests.Web;

/// <summary>
/// The app with a camera in the page: a machine profile with a <see cref="Width"/> x <see cref="Height"/> camera, and a
/// Chromium of its own whose fake capture device plays a y4m file the test writes (the fake device is a start flag, so
/// the shared browser cannot serve).
/// </summary>
internal sealed class FakeCameraApp : IAsyncDisposable
{
    public const int Width = 320;
    public const int Height = 240;

    private readonly TestFiles.TempFolder _folder = TestFiles.NewFolder();
    private readonly TestFiles.TempFolder _profile = TestFiles.NewFolder();

    private FakeCameraApp()
    {
    }

    public WebApplication App { get; private set; } = null!;

    public ChromeDriver Driver { get; private set; } = null!;

    /// <summary>Starts the app (with <paramref name="services"/> over the test services) and a Chromium playing the luma <paramref name="luma"/> writes.</summary>
    /// <param name="luma">Writes the video's frames of luma, <see cref="Width"/> x <see cref="Height"/> bytes each, to its path.</param>
    public static async Task<FakeCameraApp> StartAsync(byte[] luma, int windowWidth, int windowHeight, Action<IServiceCollection>? services = null)
    {
        var app = new FakeCameraApp();
        var video = Path.Combine(app._folder.Path, "camera.y4m");
        await WriteY4mAsync(video, luma);
        app.App = AppHost.Build([], "http://127.0.0.1:0", s =>
        {
            AppFactory.UseTestServices(s, app._folder.Path);
            services?.Invoke(s);
        });
        await app.App.StartAsync(TestContext.Current.CancellationToken);
        var profile = MachineProfile.Default with { Camera = new CameraProfile { WidthPx = Width, HeightPx = Height, UmPerPixel = 2 } };
        var profilePath = Path.Combine(app._folder.Path, "camera-profile.json");
        profile.Save(profilePath);
        app.App.Services.GetRequiredService<MainViewModel>().UseProfile(profilePath, profile);
        app.App.Services.GetRequiredService<CameraViewModel>().Refresh();

        var options = new ChromeOptions { BinaryLocation = "/usr/bin/chromium" };
        options.AddArguments(
            "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking", "--disable-dev-shm-usage",
            $"--window-size={windowWidth},{windowHeight}", "--user-data-dir=" + app._profile.Path,
            "--use-fake-ui-for-media-stream", "--use-fake-device-for-media-stream", "--use-file-for-fake-video-capture=" + video);
        var service = ChromeDriverService.CreateDefaultService("/usr/bin", "chromedriver");
        service.SuppressInitialDiagnosticInformation = true;
        app.Driver = new ChromeDriver(service, options, TimeSpan.FromSeconds(60));
        return app;
    }

    /// <summary>Opens the page as the app's window does, with a one-time launch code (a token in the address is refused).</summary>
    public void Open()
    {
        var url = App.Services.GetRequiredService<IServer>().Features.Get<IServerAddressesFeature>()!.Addresses.First().TrimEnd('/');
        Driver.Navigate().GoToUrl($"{url}/#{LaunchCodes.FragmentName}={App.Services.GetRequiredService<LaunchCodes>().Issue()}");
    }

    /// <summary>A wait for the page: polled every 50 ms for up to a minute, through elements not there yet or redrawn.</summary>
    public WebDriverWait Wait()
    {
        var wait = new WebDriverWait(Driver, TimeSpan.FromSeconds(60)) { PollingInterval = TimeSpan.FromMilliseconds(50) };
        wait.IgnoreExceptionTypes(typeof(NoSuchElementException), typeof(StaleElementReferenceException));
        return wait;
    }

    /// <summary>Saves what the page shows as <paramref name="name"/>.png with the other browser tests' screenshots.</summary>
    public void Screenshot(string name)
    {
        Directory.CreateDirectory(BrowserTest.ScreenshotFolder);
        Driver.GetScreenshot().SaveAsFile(Path.Combine(BrowserTest.ScreenshotFolder, name + ".png"));
    }

    public async ValueTask DisposeAsync()
    {
        Driver?.Quit();
        Driver?.Dispose();
        if (App is not null)
        {
            await App.StopAsync(CancellationToken.None);
            await App.DisposeAsync();
        }

        _folder.Dispose();
        _profile.Dispose();
    }

    // Two frames of 4:2:0 video, grey (chroma 128): Chromium loops the file.
    private static async Task WriteY4mAsync(string path, byte[] luma)
    {
        await using var file = File.Create(path);
        file.Write(System.Text.Encoding.ASCII.GetBytes($"YUV4MPEG2 W{Width} H{Height} F5:1 Ip A1:1 C420\n"));
        var chroma = Enumerable.Repeat((byte)128, Width * Height / 2).ToArray();
        for (var i = 0; i < 2; i++)
        {
            file.Write("FRAME\n"u8);
            file.Write(luma);
            file.Write(chroma);
        }
    }
}
