using LaserEngrave.Core.Calibration;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Tests.Calibration;

public class ProfileCalibrationTests
{
    [Fact]
    public void Load_ProfileWithoutCalibration_IsUncalibrated()
    {
        var path = Path.Combine(Path.GetTempPath(), $"le-profile-{Guid.NewGuid():N}.json");
        try
        {
            File.WriteAllText(path, """{ "name": "old profile", "spotDiameterUm": 25 }""");

            var profile = MachineProfile.Load(path);

            Assert.Null(profile.Calibration);
            Assert.Equal(25, profile.SpotDiameterUm);
            Assert.DoesNotContain("calibration", profile.ToJson(), StringComparison.Ordinal);
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public void SaveThenLoad_Calibration_RoundTrips()
    {
        var path = Path.Combine(Path.GetTempPath(), $"le-profile-{Guid.NewGuid():N}.json");
        try
        {
            var date = new DateTimeOffset(2026, 11, 23, 14, 30, 0, TimeSpan.Zero);
            var calibration = new AxisCalibration { SquarenessDegrees = 0.5, ScaleXPpm = 500, ScaleYPpm = -500, Date = date, Note = "scrap Si, 20 mm pattern" };
            (MachineProfile.Default with { Calibration = calibration }).Save(path);

            var loaded = MachineProfile.Load(path);

            Assert.Equal(calibration, loaded.Calibration);
            Assert.Contains("\"squarenessDegrees\": 0.5", File.ReadAllText(path), StringComparison.Ordinal);
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public void Load_CalibrationOutOfRange_ThrowsProfileException()
    {
        var path = Path.Combine(Path.GetTempPath(), $"le-profile-{Guid.NewGuid():N}.json");
        try
        {
            File.WriteAllText(path, """{ "calibration": { "squarenessDegrees": 30 } }""");

            var error = Assert.Throws<ProfileException>(() => MachineProfile.Load(path));
            Assert.Contains("squareness", error.Message, StringComparison.Ordinal);
        }
        finally
        {
            File.Delete(path);
        }
    }
}
