using System.Text.Json;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Cli.Tests;

public class ProcessCommandTests
{
    [Fact]
    public async Task Process_SpacingFrequencyOnePulse_PrintsSeed004Speed()
    {
        var (exit, output, _) = await CliHarness.RunAsync("process", "--spacing-um", "100", "--frequency-hz", "60000", "--pulses-per-dot", "1", "--json");

        Assert.Equal(0, exit);
        using var json = JsonDocument.Parse(output);
        Assert.Equal("speed", json.RootElement.GetProperty("solved").GetString());

        // 0.1 mm x 60 kHz / 1 = 6 m/s.
        Assert.Equal(6000, json.RootElement.GetProperty("speedMmPerS").GetDouble(), 9);
    }

    [Fact]
    public async Task Process_SpeedFrequencySpot_PrintsSpacingOverlapAndPulsesPerPixel()
    {
        var (exit, output, error) = await CliHarness.RunAsync("process", "--speed-mm-s", "1", "--frequency-hz", "1000", "--spot-um", "20", "--pitch-um", "25");

        Assert.Equal(0, exit);
        Assert.Equal(string.Empty, error);
        Assert.Contains("Pulse spacing:    1 µm", output, StringComparison.Ordinal);
        Assert.Contains("Overlap:          95 %", output, StringComparison.Ordinal);
        Assert.Contains("Pulses per pixel: 25 ", output, StringComparison.Ordinal);
    }

    [Fact]
    public async Task Process_SpacingAboveSpot_WarnsOnStderr()
    {
        var (exit, _, error) = await CliHarness.RunAsync("process", "--speed-mm-s", "30", "--frequency-hz", "1000", "--spot-um", "20");

        Assert.Equal(0, exit);
        Assert.Contains("warning: pulse spacing 30 µm is above the 20 µm spot", error, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("--speed-mm-s", "1")]
    [InlineData("--speed-mm-s", "1", "--frequency-hz", "1000", "--spacing-um", "5", "--pulses-per-dot", "1")]
    [InlineData("--speed-mm-s", "-1", "--frequency-hz", "1000")]
    [InlineData("--spacing-um", "10", "--overlap-percent", "50", "--speed-mm-s", "1")]
    [InlineData("--speed-mm-s", "fast", "--frequency-hz", "1000")]
    public async Task Process_BadOrContradictoryInput_OneLineAndExitTwo(params string[] args)
    {
        var (exit, output, error) = await CliHarness.RunAsync(["process", .. args]);

        Assert.Equal(2, exit);
        Assert.Equal(string.Empty, output);
        Assert.Single(error.Split('\n', StringSplitOptions.RemoveEmptyEntries));
    }

    [Fact]
    public async Task PlanJson_PulseFigures_FollowFromSpeedFrequencyAndPitch()
    {
        // 2 mm/s at 500 Hz: 4 µm apart; 20 µm spot: 80 % overlap; 50 µm pitch: 12.5 pulses per pixel.
        var (exit, output, _) = await CliHarness.RunAsync(
            "plan", CliHarness.BmpSuite("g/pal1.bmp"), "--pitch-um", "50", "--speed-mm-s", "2", "--frequency-hz", "500", "--json");

        Assert.Equal(0, exit);
        using var json = JsonDocument.Parse(output);
        Assert.Equal(4, json.RootElement.GetProperty("pulseSpacingUm").GetDouble(), 9);
        Assert.Equal(80, json.RootElement.GetProperty("overlapPercent").GetDouble(), 9);
        Assert.Equal(12.5, json.RootElement.GetProperty("pulsesPerPixel").GetDouble(), 9);
    }

    [Fact]
    public async Task Process_SpeedBeyondTheStage_WarnsWithTheLimit()
    {
        // 100 µm x 60 kHz = 6000 mm/s; the default T-LA60A axes are limited to 4 mm/s.
        var (exit, _, error) = await CliHarness.RunAsync("process", "--spacing-um", "100", "--frequency-hz", "60000");

        Assert.Equal(0, exit);
        Assert.Contains("warning: 6000 mm/s is above this stage's 4 mm/s", error, StringComparison.Ordinal);
    }

    [Fact]
    public async Task PlanText_CalibratedProfile_SaysTheJobIsCompensated()
    {
        var profile = CliHarness.TempFile(".json");
        try
        {
            var calibrated = LaserEngrave.Core.Geometry.MachineProfile.Default with
            {
                Calibration = new LaserEngrave.Core.Geometry.AxisCalibration { SquarenessDegrees = 0.25, ScaleXPpm = 100 },
            };
            calibrated.Save(profile);

            var (exit, output, _) = await CliHarness.RunAsync("plan", CliHarness.BmpSuite("g/pal1.bmp"), "--width-mm", "5", "--origin-mm", "5,5", "--profile", profile);

            Assert.Equal(0, exit);
            Assert.Contains("Compensated:      squareness +0.2500°, scale X +100.0 ppm, scale Y 0 ppm", output, StringComparison.Ordinal);
        }
        finally
        {
            File.Delete(profile);
        }
    }
}
