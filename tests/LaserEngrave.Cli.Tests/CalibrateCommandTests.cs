using System.Text.Json;
using LaserEngrave.Core.Calibration;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Cli.Tests;

public class CalibrateCommandTests
{
    // A machine 0.5° out of square, X +500 ppm, Y -500 ppm, measured on the default 20 mm pattern (square side 12 mm):
    // sides 12.006 and 11.994 mm, diagonals sqrt(ax² + by² ∓ 2 ax by sin 0.5°) = 16.89636 and 17.04445 mm.
    private static readonly string[] Measurements =
    [
        "--x", "8=8.0040", "--x", "16=16.0080", "--y", "8=7.9960", "--y", "16=15.9920",
        "--side-x", "12.0060", "--side-y", "11.9940", "--diagonal-ac", "16.89636", "--diagonal-bd", "17.04445", "--angle-deg", "90.5",
    ];

    [Theory]
    [InlineData(".png")]
    [InlineData(".bmp")]
    public async Task CalibratePattern_Out_WritesTheMaskThatLoadsBack(string extension)
    {
        var path = CliHarness.TempFile(extension);
        try
        {
            var (exit, output, _) = await CliHarness.RunAsync("calibrate", "pattern", "--size-mm", "5", "--pitch-um", "10", "--out", path);

            Assert.Equal(0, exit);
            Assert.Contains("Scale marks every 0.5 mm", output, StringComparison.Ordinal);
            var loaded = MaskBuilder.FromFile(path, MaskOptions.Default, out _);
            var expected = CalibrationPattern.Create(5, 10).ToMask();
            Assert.Equal((expected.Width, expected.Height, expected.CountSet()), (loaded.Width, loaded.Height, loaded.CountSet()));
            Assert.All(Enumerable.Range(0, expected.Height), y => Assert.True(expected.ReadRow(y).SequenceEqual(loaded.ReadRow(y)), $"row {y}"));
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public async Task CalibrateSolveShowClear_SyntheticMeasurements_StoreShowAndRemoveTheCalibration()
    {
        var profile = CliHarness.TempFile(".json");
        try
        {
            var (exit, _, error) = await CliHarness.RunAsync(["calibrate", "solve", "--profile", profile, "--note", "test", .. Measurements]);
            Assert.True(exit == 0, error);

            var stored = MachineProfile.Load(profile).Calibration!;
            Assert.Equal(0.5, stored.SquarenessDegrees, 3);
            Assert.Equal(500, stored.ScaleXPpm, 0);
            Assert.Equal(-500, stored.ScaleYPpm, 0);
            Assert.Equal("test", stored.Note);
            Assert.NotNull(stored.Date);

            var (_, shown, _) = await CliHarness.RunAsync("calibrate", "show", "--profile", profile, "--json");
            using (var json = JsonDocument.Parse(shown))
            {
                Assert.Equal(stored.ScaleXPpm, json.RootElement.GetProperty("calibration").GetProperty("scaleXPpm").GetDouble(), 9);
            }

            var (clearExit, _, _) = await CliHarness.RunAsync("calibrate", "clear", "--profile", profile);
            Assert.Equal(0, clearExit);
            Assert.Null(MachineProfile.Load(profile).Calibration);
        }
        finally
        {
            File.Delete(profile);
        }
    }

    [Fact]
    public async Task CalibrateSolve_PatternEngravedCompensated_RefinesTheStoredCalibration()
    {
        var profile = CliHarness.TempFile(".json");
        try
        {
            // Stored: a first, partial calibration. The residual measured with it compensating is 0.1° and +100/-100 ppm.
            var first = new AxisCalibration { SquarenessDegrees = 0.4, ScaleXPpm = 400, ScaleYPpm = -400 };
            (MachineProfile.Default with { Calibration = first }).Save(profile);
            var residual = new AxisCalibration { SquarenessDegrees = 0.1, ScaleXPpm = 100, ScaleYPpm = -100 };
            var (exit, _, error) = await CliHarness.RunAsync(
                "calibrate", "solve", "--profile", profile, "--x", "16=16.0016", "--y", "16=15.9984", "--angle-deg", "90.1");
            Assert.True(exit == 0, error);

            // The machine is then the residual after the first: M = R M0, by hand.
            var (r11, r12, r22) = residual.MachineMatrix();
            var (f11, f12, f22) = first.MachineMatrix();
            var expected = AxisCalibration.FromMachineMatrix(r11 * f11, (r11 * f12) + (r12 * f22), r22 * f22);
            var stored = MachineProfile.Load(profile).Calibration!;
            Assert.Equal(expected.SquarenessDegrees, stored.SquarenessDegrees, 6);
            Assert.Equal(expected.ScaleXPpm, stored.ScaleXPpm, 3);
            Assert.Equal(expected.ScaleYPpm, stored.ScaleYPpm, 3);
        }
        finally
        {
            File.Delete(profile);
        }
    }

    [Theory]
    [InlineData("--x", "16=16.0080", "--y", "16=15.9920")]
    [InlineData("--x", "16:16.0080", "--y", "16=15.9920", "--angle-deg", "90.5")]
    [InlineData("--x", "16=1.6008", "--y", "16=15.9920", "--angle-deg", "90.5")]
    [InlineData("--x", "16=16.0080", "--y", "16=15.9920", "--angle-deg", "90.5", "--sigma-um", "0")]
    public async Task CalibrateSolve_BadMeasurements_OneLineExitTwoProfileUntouched(params string[] args)
    {
        var profile = CliHarness.TempFile(".json");
        try
        {
            var (exit, _, error) = await CliHarness.RunAsync(["calibrate", "solve", "--profile", profile, .. args]);

            Assert.Equal(2, exit);
            Assert.Single(error.Split('\n', StringSplitOptions.RemoveEmptyEntries));
            Assert.False(File.Exists(profile));
        }
        finally
        {
            File.Delete(profile);
        }
    }

    [Fact]
    public async Task CalibrateShow_UncalibratedProfile_SaysSo()
    {
        var profile = CliHarness.TempFile(".json");
        try
        {
            MachineProfile.Default.Save(profile);

            var (exit, output, _) = await CliHarness.RunAsync("calibrate", "show", "--profile", profile);

            Assert.Equal(0, exit);
            Assert.Contains("not calibrated", output, StringComparison.Ordinal);
        }
        finally
        {
            File.Delete(profile);
        }
    }
}
