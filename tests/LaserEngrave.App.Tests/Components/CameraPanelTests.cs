using Bunit;
using LaserEngrave.App.Components.Workspace;
using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Camera;
using LaserEngrave.Core.Geometry;
using NSubstitute;
using NSubstitute.ExceptionExtensions;

namespace LaserEngrave.App.Tests.Components;

/// <summary>The Camera panel over its view-model on a fake camera service: what is drawn over the image, click to go, calibrate (issue 37).</summary>
public sealed class CameraPanelTests : ComponentTest
{
    private static readonly CameraProfile Optics = new() { WidthPx = 320, HeightPx = 240, UmPerPixel = 2, SpotOffsetXUm = 20, SpotOffsetYUm = -10 };

    private static ICameraService Service(CameraProfile? camera = null, bool twin = true)
    {
        var service = Substitute.For<ICameraService>();
        service.Camera.Returns(camera ?? Optics);
        service.IsTwin.Returns(twin);
        service.CanMove.Returns(true);
        service.StagePositionUm.Returns((10_000.0, 10_000.0));
        service.JobBoxUm.Returns((9_900.0, 9_950.0, 10_100.0, 10_050.0));
        service.TwinFrame().Returns(new CameraFrame(320, 240, new byte[320 * 240]));
        return service;
    }

    private IRenderedComponent<CameraPanel> RenderPanel(CameraViewModel camera) => Render<CameraPanel>(p => p.Add(c => c.Camera, camera));

    [Fact]
    public void Render_NoCameraSection_SaysTheProfileHasNone()
    {
        var service = Substitute.For<ICameraService>();
        service.Camera.Returns((CameraProfile?)null);

        var cut = RenderPanel(new CameraViewModel(service));

        Assert.Contains("the machine profile has no camera section", cut.Find("#camera-none").TextContent, StringComparison.Ordinal);
        Assert.Empty(cut.FindAll("#camera-view"));
    }

    [Fact]
    public void Render_TwinCamera_SpotScaleBarAndJobOutlineInCameraPixels()
    {
        var cut = RenderPanel(new CameraViewModel(Service()));

        // Spot: image centre (159.5, 119.5) + (20, -10) µm / 2 µm = (169.5, 114.5).
        var spot = cut.Find("#camera-spot");
        Assert.Equal(("169.5", "114.5"), (spot.GetAttribute("data-x"), spot.GetAttribute("data-y")));
        // A fifth of 640 µm, rounded down to 1, 2 or 5 x 10^n: 100 µm, 50 px.
        Assert.Equal("100 µm", cut.Find("#camera-scale").TextContent);
        Assert.Equal("119.5,89.5 219.5,89.5 219.5,139.5 119.5,139.5", cut.Find("#camera-job").GetAttribute("points"));
        Assert.StartsWith("data:image/png;base64,", cut.Find("#camera-image").GetAttribute("src"), StringComparison.Ordinal);
        Assert.Contains("Not calibrated (the profile's nominal optics): 2 µm a pixel", cut.Find("#camera-calibration").TextContent, StringComparison.Ordinal);
        Assert.Equal("0.0", cut.Find("#camera-sharpness").TextContent);
    }

    [Fact]
    public async Task OnCameraClick_APixel_SendsTheStageSoThatPixelComesUnderTheSpot()
    {
        var service = Service();
        var cut = RenderPanel(new CameraViewModel(service));

        await cut.InvokeAsync(() => cut.Instance.OnCameraClick(179.5, 104.5));

        cut.WaitForAssertion(() => service.Received(1).GoToAsync(10_020, 9_980, Arg.Any<CancellationToken>()));
        cut.WaitForAssertion(() => Assert.Contains("Going to 10.02, 9.98 mm (pixel 180, 105), laser off", cut.Find("#camera-goto").TextContent, StringComparison.Ordinal));
    }

    [Fact]
    public async Task OnCameraClick_MoveRefused_ShowsTheReason()
    {
        var service = Service();
        service.GoToAsync(Arg.Any<double>(), Arg.Any<double>(), Arg.Any<CancellationToken>()).ThrowsAsync(new CameraException("X 70 mm is outside the travel 0..60 mm"));
        var cut = RenderPanel(new CameraViewModel(service));

        await cut.InvokeAsync(() => cut.Instance.OnCameraClick(10, 10));

        cut.WaitForAssertion(() => Assert.Equal("X 70 mm is outside the travel 0..60 mm", cut.Find("[data-error=camera]").TextContent));
    }

    [Fact]
    public void Calibrate_OnTheTwin_ShowsWhatWasMeasured()
    {
        var service = Service();
        var measured = Optics.Nominal with { UmPerPixel = 1.9987, RotationDeg = 0.012, ResidualUm = 0.04 };
        service.CalibrateAsync(Arg.Any<CancellationToken>()).Returns(new CameraCalibrationResult(measured, new CalibrationJog[8], 150));
        var cut = RenderPanel(new CameraViewModel(service));

        cut.Find("#camera-calibrate").Click();

        cut.WaitForAssertion(() => Assert.Equal(4, cut.FindAll("[data-camera=calibration]").Count));
        var lines = cut.FindAll("[data-camera=calibration]").Select(e => e.TextContent).ToList();
        Assert.Equal("Scale: 1.9987 µm a camera pixel", lines[0]);
        Assert.Equal("Rotation: 0.012° against the stage's X", lines[1]);
        Assert.Equal("Residual: 0.04 µm over 8 jogs", lines[3]);
    }

    [Fact]
    public void Calibrate_LiveCameraNotPlayingYet_DisabledWithTheReason()
    {
        var cut = RenderPanel(new CameraViewModel(Service(twin: false)));

        var button = cut.Find("#camera-calibrate");

        Assert.True(button.HasAttribute("disabled"));
        Assert.Equal("Calibrate: the live camera is not playing yet: allow the browser to use it", button.GetAttribute("title"));
        Assert.NotEmpty(cut.FindAll("#camera-video"));
    }

    [Fact]
    public void Calibrate_LiveCameraPlaying_OfferedWithItsFrames()
    {
        var camera = new CameraViewModel(Service(twin: false));
        var cut = RenderPanel(camera);

        cut.InvokeAsync(() => camera.ReportLiveCamera("USB microscope (320 x 240)", null));

        cut.WaitForAssertion(() => Assert.False(cut.Find("#camera-calibrate").HasAttribute("disabled")));
        Assert.Equal("Live: USB microscope (320 x 240)", cut.Find("#camera-source").TextContent);
    }
}
