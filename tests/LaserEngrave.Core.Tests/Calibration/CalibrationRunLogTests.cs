using System.Text.Json;
using LaserEngrave.Core.Calibration;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Calibration;

public class CalibrationRunLogTests
{
    [Fact]
    public void Serialize_CalibratedProfileAndDotProcess_LoggedAndReadBack()
    {
        var image = Path.Combine(Path.GetTempPath(), $"le-cal-log-{Guid.NewGuid():N}.bmp");
        File.Copy(Logging.TestRuns.Asset("qr-code.bmp"), image);
        try
        {
            Check(image);
        }
        finally
        {
            File.Delete(image);
        }
    }

    private static void Check(string image)
    {
        var calibration = new AxisCalibration { SquarenessDegrees = 0.5, ScaleXPpm = 500, ScaleYPpm = -500, Date = new DateTimeOffset(2026, 11, 23, 12, 0, 0, TimeSpan.Zero), Note = "n" };
        var spec = new JobSpec
        {
            ImagePath = image,
            Size = SizeSpec.Width(5),
            Profile = MachineProfile.Default with { Calibration = calibration },
            Process = ProcessSettings.Default with { Mode = PlanMode.Dots, PulsesPerDot = 3, PulseEnergyUj = 2.5 },
        };
        var record = RunRecord.ForJob(PreparedJob.Prepare(spec), "00", new DateTimeOffset(2026, 11, 23, 14, 0, 0, TimeSpan.Zero));

        var json = RunRecordJson.Serialize(record);
        var back = RunRecordJson.Deserialize(json, "test");

        using var document = JsonDocument.Parse(json);
        Assert.Equal("dots", document.RootElement.GetProperty("process").GetProperty("mode").GetString());
        Assert.Equal(0.5, document.RootElement.GetProperty("profile").GetProperty("calibration").GetProperty("squarenessDegrees").GetDouble());
        Assert.Equal(calibration, back.Profile.Calibration);
        Assert.Equal(spec.Process, back.Process);
    }
}
