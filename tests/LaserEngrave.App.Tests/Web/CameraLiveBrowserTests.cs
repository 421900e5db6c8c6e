using System.Globalization;
using LaserEngrave.Core.Camera;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Camera;
using OpenQA.Selenium;

namespace LaserEngrave.App.Tests.Web;

/// <summary>
/// The Camera panel with a camera in the page: Chromium's fake capture device plays a y4m file this test writes (frames
/// of the twin's camera), through getUserMedia as any camera would (issue 37). Its own Chromium: the fake device is a
/// start flag.
/// </summary>
public sealed class CameraLiveBrowserTests : IAsyncLifetime
{
    private const int Width = FakeCameraApp.Width;
    private const int Height = FakeCameraApp.Height;
    private FakeCameraApp? _camera;
    private CameraFrame? _frame;

    public async ValueTask InitializeAsync()
    {
        _frame = await TwinFrameAsync();
        // Video levels: the browser decodes luma 16..235 as black..white, so the page sees the twin's grey levels again.
        _camera = await FakeCameraApp.StartAsync([.. _frame.Pixels.Select(v => (byte)Math.Round(16 + (v * 219.0 / 255)))], 1280, 900);
    }

    public async ValueTask DisposeAsync()
    {
        if (_camera is not null)
        {
            await _camera.DisposeAsync();
        }
    }

    [Fact]
    public void CameraPanel_FakeCaptureDevice_ShowsTheLiveImageWithItsSharpness()
    {
        var driver = _camera!.Driver;
        // As the app's window opens it: a one-time launch code the page trades for the token (a token in the address is refused).
        _camera.Open();
        var wait = _camera.Wait();
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
        _camera.Screenshot("camera-live");
    }

    // A frame of the twin's camera looking at a mark.
    private static async Task<CameraFrame> TwinFrameAsync()
    {
        var profile = MachineProfile.Default with { Camera = new CameraProfile { WidthPx = Width, HeightPx = Height, UmPerPixel = 2 } };
        await using var machine = SimulatedMachine.CreateInProcess(profile);
        var camera = new TwinCamera(machine);
        camera.AddMark(20_000, 20_000, 40);
        return camera.Render(20_000, 20_000, 0, 1);
    }
}
