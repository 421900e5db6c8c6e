using LaserEngrave.Core.Camera;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Tests.Camera;

public class CameraProfileTests
{
    public static TheoryData<string, string> BadCameras => new()
    {
        { """{ "camera": { "umPerPixel": 0 } }""", "camera.umPerPixel must be above 0 and at most 1000 µm on the sample per camera pixel (got 0)" },
        { """{ "camera": { "widthPx": 8 } }""", "camera.widthPx must be 16..8192 pixels (got 8)" },
        { """{ "camera": { "heightPx": 9000 } }""", "camera.heightPx must be 16..8192 pixels (got 9000)" },
        { """{ "camera": { "rotationDeg": 270 } }""", "camera.rotationDeg must be above -180 and at most 180 degrees (got 270)" },
        { """{ "camera": { "spotOffsetXUm": 500 } }""", "camera.spotOffsetXUm must lie inside the image, less than 480 µm from its centre either way (got 500)" },
        { """{ "camera": { "calibration": { "umPerPixel": 1.5, "spotXPx": 700, "spotYPx": 10 } } }""", "camera.calibration.spotXPx must lie inside the image, 0..639 (got 700)" },
        { """{ "camera": { "umperpixel": 1 } }""", "camera.umperpixel is not a field of the machine profile" },
    };

    [Theory]
    [MemberData(nameof(BadCameras))]
    public void Load_BadCameraField_OneLineNamingTheField(string json, string expected)
    {
        var path = Path.Combine(Path.GetTempPath(), $"profile-{Guid.NewGuid():N}.json");
        try
        {
            File.WriteAllText(path, json);
            var ex = Assert.Throws<ProfileException>(() => MachineProfile.Load(path));
            Assert.Contains(expected, ex.Message, StringComparison.Ordinal);
            Assert.DoesNotContain('\n', ex.Message);
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public void Load_CameraWithCalibrationSaved_LoadsBackEqual()
    {
        var path = Path.Combine(Path.GetTempPath(), $"profile-{Guid.NewGuid():N}.json");
        try
        {
            var camera = new CameraProfile
            {
                WidthPx = 320, HeightPx = 240, UmPerPixel = 2.5, RotationDeg = -3, Mirrored = true, SpotOffsetXUm = 12, SpotOffsetYUm = -7,
                Calibration = new CameraCalibration { UmPerPixel = 2.49, RotationDeg = -2.95, Mirrored = true, SpotXPx = 164.2, SpotYPx = 116.1, ResidualUm = 0.3 },
            };
            (MachineProfile.Default with { Camera = camera }).Save(path);
            Assert.Equal(camera, MachineProfile.Load(path).Camera);
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public void ToJson_NoCamera_LeavesTheSectionOut()
    {
        Assert.DoesNotContain("camera", MachineProfile.Default.ToJson(), StringComparison.Ordinal);
    }

    [Theory]
    [InlineData(0, false)]
    [InlineData(30, false)]
    [InlineData(-120, true)]
    public void PixelAt_OffsetUmOfAPixel_ComesBackToThePixel(double rotationDeg, bool mirrored)
    {
        var calibration = new CameraCalibration { UmPerPixel = 1.7, RotationDeg = rotationDeg, Mirrored = mirrored, SpotXPx = 300.5, SpotYPx = 211.25 };

        var (dx, dy) = calibration.OffsetUm(17.25, 402.5);
        var (x, y) = calibration.PixelAt(dx, dy);

        Assert.Equal(17.25, x, 9);
        Assert.Equal(402.5, y, 9);
        Assert.Equal(1.7 * Math.Sqrt(Math.Pow(17.25 - 300.5, 2) + Math.Pow(402.5 - 211.25, 2)), Math.Sqrt((dx * dx) + (dy * dy)), 9);
    }

    [Fact]
    public void StageTargetUm_TurnedA90Degrees_MovesAlongStageY()
    {
        var calibration = new CameraCalibration { UmPerPixel = 2, RotationDeg = 90, SpotXPx = 100, SpotYPx = 100 };

        var (x, y) = calibration.StageTargetUm(5000, 6000, 110, 100);

        Assert.Equal(5000, x, 9);
        Assert.Equal(6020, y, 9);
    }
}
