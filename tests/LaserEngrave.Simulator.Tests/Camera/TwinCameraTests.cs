using LaserEngrave.Core.Camera;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator.Camera;

namespace LaserEngrave.Simulator.Tests.Camera;

public class TwinCameraTests
{
    internal static MachineProfile Profile(CameraProfile? camera = null, bool withZ = true) => MachineProfile.Default with
    {
        Camera = camera ?? new CameraProfile { WidthPx = 320, HeightPx = 240, UmPerPixel = 1.5 },
        Z = withZ ? new ZAxisProfile() : null,
    };

    [Fact]
    public async Task Render_SameSeedAndFrameNumber_SameImage()
    {
        await using var a = SimulatedMachine.CreateInProcess(Profile());
        await using var b = SimulatedMachine.CreateInProcess(Profile());

        var first = new TwinCamera(a).Render(10_000, 12_000, 0, 5);
        var second = new TwinCamera(b).Render(10_000, 12_000, 0, 5);
        var otherSeed = new TwinCamera(b, new TwinCameraOptions { Seed = 38 }).Render(10_000, 12_000, 0, 5);

        Assert.Equal(first.Pixels, second.Pixels);
        Assert.NotEqual(first.Pixels, otherSeed.Pixels);
    }

    [Fact]
    public async Task Render_StageMovedTenPixelsAlongX_ImageMovesTenPixelsTheOtherWay()
    {
        await using var machine = SimulatedMachine.CreateInProcess(Profile());
        var camera = new TwinCamera(machine, new TwinCameraOptions { NoiseGrey = 0 });

        var before = camera.Render(10_000, 12_000, 0, 1);
        var after = camera.Render(10_000 + 15, 12_000, 0, 2);

        // The sample point at pixel u + 10 before is at pixel u after; away from the blur's clamped border they agree.
        var worst = 0;
        for (var v = 20; v < 220; v++)
        {
            for (var u = 20; u < 280; u++)
            {
                worst = Math.Max(worst, Math.Abs(before[u + 10, v] - after[u, v]));
            }
        }

        Assert.True(worst <= 1, $"pixels differ by up to {worst} grey levels");
        Assert.True(Spread(before) > 20, $"the sample has too little texture: spread {Spread(before):F1}");
    }

    [Fact]
    public async Task Render_Defocused_LosesSharpness()
    {
        await using var machine = SimulatedMachine.CreateInProcess(Profile());
        var camera = new TwinCamera(machine);

        var sharp = FocusMeasure.Sharpness(camera.Render(10_000, 12_000, 0, 1));
        var blurred = FocusMeasure.Sharpness(camera.Render(10_000, 12_000, 200, 1));

        Assert.True(blurred < sharp / 3, $"sharpness {blurred:F2} defocused against {sharp:F2} in focus");
    }

    [Fact]
    public async Task Capture_AfterATestDot_DarkSpotAtTheSpotPixel()
    {
        var optics = new CameraProfile { WidthPx = 320, HeightPx = 240, UmPerPixel = 1.5, SpotOffsetXUm = 30, SpotOffsetYUm = -15 };
        await using var machine = SimulatedMachine.CreateInProcess(Profile(optics));
        var camera = new TwinCamera(machine);
        var rig = new TwinCameraRig(machine, camera);
        await rig.MoveToAsync(20_000, 20_000, CancellationToken.None);
        await TwinCameraTests.FocusAsync(rig);

        var before = camera.Capture();
        await rig.FireDotAsync(CancellationToken.None);
        var after = camera.Capture();

        // Spot pixel: centre (159.5, 119.5) + (30, -15) µm / 1.5 µm = (179.5, 109.5).
        Assert.True(before[180, 110] - after[180, 110] > 60, $"no dark dot at the spot: {before[180, 110]} -> {after[180, 110]}");
        Assert.True(Math.Abs(before[100, 200] - after[100, 200]) < 12, "the image changed far from the dot");
    }

    [Fact]
    public async Task Capture_LaserFiredByTheGate_BurnDrawnWhereTheStageStood()
    {
        await using var machine = SimulatedMachine.CreateInProcess(Profile(withZ: false));
        var camera = new TwinCamera(machine);
        var rig = new TwinCameraRig(machine, camera);
        await rig.MoveToAsync(20_000, 20_000, CancellationToken.None);
        await TwinCameraTests.FocusAsync(rig);
        var before = camera.Capture();

        machine.Recorder.RecordLaser(0, 1000);
        machine.Recorder.RecordLaser(0.005, 0);
        var after = camera.Capture();

        Assert.True(before[160, 120] - after[160, 120] > 60, $"no burn at the spot: {before[160, 120]} -> {after[160, 120]}");
    }

    /// <summary>Z where the twin's camera sees sharpest (a no-op without Z).</summary>
    internal static async Task FocusAsync(TwinCameraRig rig)
    {
        if (rig.HasFocusAxis)
        {
            await rig.MoveFocusAsync(rig.Camera.Options.CameraFocusOffsetUm, CancellationToken.None);
        }
    }

    internal static double Spread(CameraFrame frame)
    {
        var values = frame.ToDoubles();
        var mean = values.Average();
        return Math.Sqrt(values.Sum(v => (v - mean) * (v - mean)) / values.Length);
    }
}
