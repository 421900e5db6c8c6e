using Bunit;
using LaserEngrave.App.Components.Workspace;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator;
using NSubstitute;

namespace LaserEngrave.App.Tests.Components;

/// <summary>The Camera panel on the app's own simulator connection (virtual time, unpaced): what the panel's buttons do end to end (issue 37).</summary>
public sealed class CameraSimulatorTests : ComponentTest
{
    public CameraSimulatorTests()
    {
        // The real twin instead of the fakes, in unpaced virtual time as the browser tests run it.
        var factory = new MachineConnectionFactory(new SimulatorOptions());
        Machine.Factory.ConnectAsync(Arg.Any<MachineChoice>(), Arg.Any<MachineProfile>(), Arg.Any<CancellationToken>())
            .Returns(c => factory.ConnectAsync(c.Arg<MachineChoice>(), c.Arg<MachineProfile>(), c.Arg<CancellationToken>()));
    }

    [Fact]
    public async Task Calibrate_OnTheSimulator_MeasuresTheTwinsOpticsWithoutADeadlock()
    {
        await ConnectAsync();
        Main.TestMoves.GoToXMm = 30;
        Main.TestMoves.GoToYMm = 30;
        await Main.TestMoves.GoToCommand.ExecuteAsync(null);
        Assert.Null(Main.TestMoves.Error);
        var cut = Render<CameraPanel>(p => p.Add(c => c.Camera, Camera));

        cut.Find("#camera-calibrate").Click();

        cut.WaitForAssertion(() => Assert.True(cut.FindAll("[data-camera=calibration]").Count == 4 || cut.FindAll("[data-error=camera]").Count > 0), TimeSpan.FromSeconds(120));
        Assert.Empty(cut.FindAll("[data-error=camera]").Select(e => e.TextContent));
        Assert.StartsWith("Calibrated: ", cut.Find("#camera-calibration").TextContent, StringComparison.Ordinal);
        // The twin's optics are the default camera's (the default profile has no camera section): measured, not copied.
        var truth = new CameraProfile().Nominal;
        var measured = Camera.InForce!;
        Assert.True(Math.Abs((measured.UmPerPixel / truth.UmPerPixel) - 1) < 0.005, $"scale {measured.UmPerPixel} µm a pixel, the twin's is {truth.UmPerPixel}");
        Assert.True(Math.Abs(measured.RotationDeg - truth.RotationDeg) < 0.1, $"rotation {measured.RotationDeg}°, the twin's is {truth.RotationDeg}°");
        Assert.True(measured.ResidualUm < 2, $"residual {measured.ResidualUm} µm");
        Assert.Null(Main.TestMoves.Error);
    }

    [Fact]
    public async Task ScanMap_OnTheSimulator_StitchedMapShownWithItsSeamsAndTheStageBack()
    {
        await ConnectAsync();
        Main.TestMoves.GoToXMm = 30;
        Main.TestMoves.GoToYMm = 30;
        await Main.TestMoves.GoToCommand.ExecuteAsync(null);
        var before = (Main.Machine.XMicrosteps, Main.Machine.YMicrosteps);
        var cut = Render<CameraPanel>(p => p.Add(c => c.Camera, Camera));
        Camera.MapSizeMm = 0.5;

        cut.Find("#camera-map").Click();

        cut.WaitForAssertion(() => Assert.True(cut.FindAll("#camera-map-result").Count == 1 || cut.FindAll("[data-error=camera]").Count > 0), TimeSpan.FromSeconds(120));
        Assert.Empty(cut.FindAll("[data-error=camera]").Select(e => e.TextContent));
        var text = cut.Find("#camera-map-result").TextContent;
        Assert.Matches(@"^Map: \d+ frames, worst seam (0|1)(\.\d+)? camera px over \d+ seams; ", text);
        Assert.StartsWith("data:image/png;base64,", cut.Find("#camera-map-image").GetAttribute("src"), StringComparison.Ordinal);
        // Centred where the stage stood, half a millimetre a side; the stage back there.
        var (x, y, w, h) = Camera.MapBoxMm!.Value;
        Assert.Equal(29.75, x, 0.01);
        Assert.Equal(29.75, y, 0.01);
        Assert.Equal(0.5, w, 0.02);
        Assert.Equal(0.5, h, 0.02);
        Assert.Equal(before, (Main.Machine.XMicrosteps, Main.Machine.YMicrosteps));
    }
}
