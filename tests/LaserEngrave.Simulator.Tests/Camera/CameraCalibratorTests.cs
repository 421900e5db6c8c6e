using LaserEngrave.Core.Camera;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator.Camera;

namespace LaserEngrave.Simulator.Tests.Camera;

/// <summary>Calibration on the twin's camera recovers the optics the twin was given (issue 37: 0.5 %, 0.1°, 2 µm).</summary>
public class CameraCalibratorTests
{
    public static TheoryData<double, double, bool, double, double> Optics => new()
    {
        { 1.37, 2.3, false, 23, -14 },
        { 2.1, -37.5, true, -41, 30 },
        { 0.85, 178, false, 0, 0 },
    };

    [Theory]
    [MemberData(nameof(Optics))]
    public async Task CalibrateAsync_TwinWithKnownOptics_RecoversScaleRotationAndSpot(double umPerPixel, double rotationDeg, bool mirrored, double spotXUm, double spotYUm)
    {
        var optics = new CameraProfile { WidthPx = 320, HeightPx = 240, UmPerPixel = umPerPixel, RotationDeg = rotationDeg, Mirrored = mirrored, SpotOffsetXUm = spotXUm, SpotOffsetYUm = spotYUm };
        await using var machine = SimulatedMachine.CreateInProcess(TwinCameraTests.Profile(optics));
        var camera = new TwinCamera(machine);
        var rig = new TwinCameraRig(machine, camera);
        await rig.MoveToAsync(20_000, 25_000, CancellationToken.None);
        await TwinCameraTests.FocusAsync(rig);
        var guess = optics.Nominal with { UmPerPixel = umPerPixel * 1.1, SpotXPx = 160, SpotYPx = 120 };

        var result = await new CameraCalibrator(rig).CalibrateAsync(guess, fireDot: true, CancellationToken.None);

        var truth = camera.Truth;
        var measured = result.Calibration;
        var scaleErrorPercent = 100 * (measured.UmPerPixel / truth.UmPerPixel - 1);
        var rotationErrorDeg = Math.IEEERemainder(measured.RotationDeg - truth.RotationDeg, 360);
        var spotErrorUm = Math.Sqrt(Math.Pow(measured.SpotXPx - truth.SpotXPx, 2) + Math.Pow(measured.SpotYPx - truth.SpotYPx, 2)) * truth.UmPerPixel;
        TestContext.Current.TestOutputHelper?.WriteLine(
            $"scale error {scaleErrorPercent:F4} %, rotation error {rotationErrorDeg:F4}°, spot error {spotErrorUm:F3} µm, residual {measured.ResidualUm:F3} µm");
        Assert.Equal(mirrored, measured.Mirrored);
        Assert.True(Math.Abs(scaleErrorPercent) < 0.5, $"scale off by {scaleErrorPercent:F3} %");
        Assert.True(Math.Abs(rotationErrorDeg) < 0.1, $"rotation off by {rotationErrorDeg:F3}°");
        Assert.True(spotErrorUm < 2, $"spot off by {spotErrorUm:F2} µm");
        Assert.True(measured.ResidualUm < 1, $"residual {measured.ResidualUm:F2} µm");
        Assert.Equal((20_000, 25_000), (Math.Round(rig.Position.XUm), Math.Round(rig.Position.YUm)));
    }

    [Fact]
    public async Task CalibrateAsync_BlankSample_RefusedWithAPlainSentence()
    {
        await using var machine = SimulatedMachine.CreateInProcess(TwinCameraTests.Profile());
        var camera = new TwinCamera(machine, new TwinCameraOptions { Contrast = 0.005 });
        var rig = new TwinCameraRig(machine, camera);
        await rig.MoveToAsync(20_000, 25_000, CancellationToken.None);
        await TwinCameraTests.FocusAsync(rig);

        var ex = await Assert.ThrowsAsync<CameraException>(() => new CameraCalibrator(rig).CalibrateAsync(camera.Profile.Nominal, fireDot: true, CancellationToken.None));

        Assert.StartsWith("the image has too little texture to track: its brightness varies by only", ex.Message, StringComparison.Ordinal);
        Assert.DoesNotContain('\n', ex.Message);
        Assert.Equal(0, rig.Moves - 1);
        Assert.Empty(camera.Marks);
    }

    [Fact]
    public async Task CalibrateAsync_DotTooFaint_RefusedAndTheStageBackAtTheStart()
    {
        await using var machine = SimulatedMachine.CreateInProcess(TwinCameraTests.Profile());
        var camera = new TwinCamera(machine, new TwinCameraOptions { PulsesToHalve = 10_000 });
        var rig = new TwinCameraRig(machine, camera);
        await rig.MoveToAsync(20_000, 25_000, CancellationToken.None);
        await TwinCameraTests.FocusAsync(rig);

        var ex = await Assert.ThrowsAsync<CameraException>(() => new CameraCalibrator(rig).CalibrateAsync(camera.Profile.Nominal, fireDot: true, CancellationToken.None));

        Assert.StartsWith("the test dot did not show in the image", ex.Message, StringComparison.Ordinal);
        Assert.Equal((20_000, 25_000), (Math.Round(rig.Position.XUm), Math.Round(rig.Position.YUm)));
    }
}
