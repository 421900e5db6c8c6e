using LaserEngrave.Core.Alignment;
using LaserEngrave.Core.Camera;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator.Camera;

namespace LaserEngrave.Simulator.Tests.Camera;

/// <summary>Click-to-go, marks picked in the image, the focus sweep and the stitched map, on the twin's camera with a calibration the app measured (issue 37).</summary>
public class CameraNavigationTests
{
    private static readonly CameraProfile Optics = new() { WidthPx = 320, HeightPx = 240, UmPerPixel = 1.37, RotationDeg = 2.3, SpotOffsetXUm = 23, SpotOffsetYUm = -14 };

    private static void Report(string line) => TestContext.Current.TestOutputHelper?.WriteLine(line);

    // The twin, focused, at (x, y), with the camera calibrated by the app (not given the truth).
    private static async Task<(SimulatedMachine Machine, TwinCamera Camera, TwinCameraRig Rig, CameraCalibration Calibration)> CalibratedAsync(CameraProfile optics, double x, double y)
    {
        var machine = SimulatedMachine.CreateInProcess(TwinCameraTests.Profile(optics));
        var camera = new TwinCamera(machine);
        var rig = new TwinCameraRig(machine, camera);
        await TwinCameraTests.FocusAsync(rig);
        await rig.MoveToAsync(x - 3000, y - 3000, CancellationToken.None);
        var result = await new CameraCalibrator(rig).CalibrateAsync(optics.Nominal with { UmPerPixel = optics.UmPerPixel * 1.05 }, fireDot: true, CancellationToken.None);
        await rig.MoveToAsync(x, y, CancellationToken.None);
        return (machine, camera, rig, result.Calibration);
    }

    [Fact]
    public async Task GoToPixelAsync_ClickOnAMark_MarkLandsUnderTheSpotWithinTwoMicrometres()
    {
        var (machine, camera, rig, calibration) = await CalibratedAsync(Optics, 20_000, 25_000);
        await using var _ = machine;
        var navigator = new CameraNavigator(rig, calibration);
        var worst = 0.0;
        foreach (var (mx, my) in new[] { (20_110.0, 24_930.0), (19_850.0, 25_120.0), (20_020.0, 25_010.0) })
        {
            await rig.MoveToAsync(20_000, 25_000, CancellationToken.None);
            camera.AddMark(mx, my, 20);
            var frame = await rig.CaptureAsync(CancellationToken.None);
            var (tx, ty) = camera.Truth.PixelAt(mx - 20_000, my - 25_000);

            // A hand's click: on the mark's pixel, a few pixels off its centre; the snap finds the centre.
            var picked = navigator.PickMark(frame, Math.Round(tx) + 3, Math.Round(ty) - 2, 20);
            var (x, y) = await navigator.GoToPixelAsync(picked.XPx, picked.YPx, CancellationToken.None);

            var error = Math.Sqrt(Math.Pow(x - mx, 2) + Math.Pow(y - my, 2));
            worst = Math.Max(worst, error);
            Assert.True(error < 2, $"click-to-go landed {error:F2} µm from the mark at {mx}, {my}");
        }

        Report($"click-to-go: worst {worst:F3} µm from the mark");
    }

    [Fact]
    public async Task PickFiducial_TwoMarksPickedInTheImage_AlignTheJobWithinFiveMicrometres()
    {
        var (machine, camera, rig, calibration) = await CalibratedAsync(Optics, 20_000, 25_000);
        await using var _ = machine;
        var navigator = new CameraNavigator(rig, calibration);
        var truth = new RigidTransform(7.3 * Math.PI / 180, 18.2, 21.7);
        (double X, double Y)[] jobMarks = [(1.0, 1.5), (9.0, 6.5)];
        var fiducials = new List<Fiducial>();
        foreach (var (jx, jy) in jobMarks)
        {
            var (sx, sy) = truth.Apply(jx, jy);
            camera.AddMark(sx * 1000, sy * 1000, 30);

            // Jog near the mark (80 µm off, as by eye on the jog pad), look, click near it.
            var (nearX, nearY) = ((sx * 1000) + 80, (sy * 1000) - 60);
            await rig.MoveToAsync(nearX, nearY, CancellationToken.None);
            var (px, py) = camera.Truth.PixelAt((sx * 1000) - rig.Position.XUm, (sy * 1000) - rig.Position.YUm);
            var frame = await rig.CaptureAsync(CancellationToken.None);
            fiducials.Add(navigator.PickFiducial(frame, Math.Round(px) - 2, Math.Round(py) + 4, 30, jx, jy));
        }

        var alignment = FiducialAlignment.Solve(fiducials[0], fiducials[1]);

        // Every corner of a 10 x 8 mm job and both marks land within 5 µm of where the true transform puts them.
        var worst = 0.0;
        foreach (var (jx, jy) in new[] { (0.0, 0.0), (10.0, 0.0), (0.0, 8.0), (10.0, 8.0), jobMarks[0], jobMarks[1] })
        {
            var (ax, ay) = alignment.Transform.Apply(jx, jy);
            var (tx, ty) = truth.Apply(jx, jy);
            worst = Math.Max(worst, 1000 * Math.Sqrt(Math.Pow(ax - tx, 2) + Math.Pow(ay - ty, 2)));
        }

        Report($"alignment from marks picked in the image: worst {worst:F3} µm over the job's corners and marks, rotation {alignment.Transform.AngleDegrees:F4}° (true 7.3°)");
        Assert.True(worst < 5, $"the aligned job is up to {worst:F2} µm off");
    }

    [Fact]
    public async Task RunAsync_FocusSweep_FindsTheTwinsFocusWithinOneStep()
    {
        await using var machine = SimulatedMachine.CreateInProcess(TwinCameraTests.Profile(Optics));
        var camera = new TwinCamera(machine);
        var rig = new TwinCameraRig(machine, camera);
        await rig.MoveToAsync(20_000, 25_000, CancellationToken.None);
        const double step = 50;

        var result = await new FocusSweep(rig).RunAsync(-500, 600, step, CancellationToken.None);

        var truth = camera.Options.CameraFocusOffsetUm;
        Report($"focus sweep: sharpest step {result.BestStepUm} µm, peak {result.BestOffsetUm:F1} µm, the twin's focus {truth} µm, step {step} µm");
        Assert.True(Math.Abs(result.BestOffsetUm - truth) < step, $"the sweep found {result.BestOffsetUm:F1} µm, the twin's focus is {truth} µm");
        Assert.True(Math.Abs(result.BestStepUm - truth) <= step, $"the sharpest step {result.BestStepUm} µm is more than a step from {truth} µm");
        Assert.Equal(result.BestStepUm, rig.FocusOffsetUm, 0.5);
    }

    [Fact]
    public async Task RunAsync_NoFocusAxis_RefusedWithAPlainSentence()
    {
        await using var machine = SimulatedMachine.CreateInProcess(TwinCameraTests.Profile(Optics, withZ: false));
        var rig = new TwinCameraRig(machine, new TwinCamera(machine));

        var ex = await Assert.ThrowsAsync<CameraException>(() => new FocusSweep(rig).RunAsync(-100, 100, 10, CancellationToken.None));

        Assert.Equal("a focus sweep needs a focus (Z) axis, and the machine profile has none", ex.Message);
    }

    [Fact]
    public async Task ScanAsync_FourByFourMillimetres_SeamsUnderTwoCameraPixels()
    {
        var optics = new CameraProfile { WidthPx = 400, HeightPx = 300, UmPerPixel = 2.5, RotationDeg = -1.7, SpotOffsetXUm = 40, SpotOffsetYUm = 25 };
        var (machine, camera, rig, calibration) = await CalibratedAsync(optics, 20_000, 25_000);
        await using var _ = machine;

        var map = await new MapStitcher(rig, calibration).ScanAsync(20_000, 25_000, 4000, 4000, 5, CancellationToken.None);

        // The map in stage axes: a mark put on the sample before the scan would be where its stage position says.
        Report($"map: {map.Frames.Count} frames, {map.Seams.Count} seams, worst seam {map.WorstSeamPx:F3} camera pixels, map {map.Image.Width} x {map.Image.Height} px at {map.UmPerPixel} µm");
        Assert.True(map.Frames.Count >= 16, $"only {map.Frames.Count} frames");
        Assert.True(map.Seams.Count >= 24, $"only {map.Seams.Count} seams");
        Assert.True(map.WorstSeamPx < 2, $"a seam is {map.WorstSeamPx:F2} camera pixels off");
        Assert.Equal(801, map.Image.Width);
    }

    [Fact]
    public async Task ScanAsync_MarkOnTheSample_DrawnAtItsStagePositionInTheMap()
    {
        var optics = new CameraProfile { WidthPx = 400, HeightPx = 300, UmPerPixel = 2.5, RotationDeg = -1.7 };
        var (machine, camera, rig, calibration) = await CalibratedAsync(optics, 20_000, 25_000);
        await using var _ = machine;
        camera.AddMark(21_000, 25_500, 40);

        var map = await new MapStitcher(rig, calibration).ScanAsync(20_000, 25_000, 2000, 1000, 5, CancellationToken.None);

        // Map pixel (200, 100) is stage (21000, 25500).
        var (x, y) = MarkFinder.Locate(map.Image, 203, 98, 10, 8);
        var errorUm = Math.Sqrt(Math.Pow(x - 200, 2) + Math.Pow(y - 100, 2)) * map.UmPerPixel;
        Report($"mark in the map {errorUm:F2} µm from its stage position");
        Assert.True(errorUm < 5, $"the mark is drawn {errorUm:F1} µm from its stage position");
    }
}
