using LaserEngrave.App.Services;
using LaserEngrave.App.Tests.Components;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator;
using Microsoft.Extensions.DependencyInjection;
using OpenQA.Selenium;

namespace LaserEngrave.App.Tests.Web;

/// <summary>
/// A live camera's frames from the page to the app in Chromium: the fake capture device plays a blank y4m this test writes,
/// the simulator is taken for a real machine (its twin hidden), and Calibrate asks the page for frames, which the app
/// measures and refuses with its plain sentence (issue 37).
/// </summary>
public sealed class CameraLiveFramesBrowserTests : IAsyncLifetime
{
    private const int Width = FakeCameraApp.Width;
    private const int Height = FakeCameraApp.Height;
    private FakeCameraApp? _camera;

    // A grey card in front of the camera: luma 126 and 127 in a fine check, nothing to track.
    public async ValueTask InitializeAsync() =>
        _camera = await FakeCameraApp.StartAsync(
            [.. Enumerable.Range(0, Width * Height).Select(i => (byte)(126 + ((i + (i / Width)) % 2)))],
            1366,
            768,
            services => services.AddSingleton<IMachineConnectionFactory>(new HiddenTwinFactory()));

    public async ValueTask DisposeAsync()
    {
        if (_camera is not null)
        {
            await _camera.DisposeAsync();
        }
    }

    [Fact]
    public void Calibrate_BlankLiveCamera_FramesReachTheAppWhichRefusesForTooLittleTexture()
    {
        var driver = _camera!.Driver;
        _camera.Open();
        driver.ExecuteCdpCommand("Emulation.setDeviceMetricsOverride", new Dictionary<string, object?>
        {
            ["width"] = 1366, ["height"] = 768, ["deviceScaleFactor"] = 1, ["mobile"] = false,
        });
        var wait = _camera.Wait();
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
        Assert.Equal(1, _camera.App.Services.GetRequiredService<CameraViewModel>().LiveFramesReceived);
        driver.ExecuteScript("document.querySelector('[data-error=camera]').scrollIntoView({ block: 'end' });");
        _camera.Screenshot("camera-live-blank");
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
