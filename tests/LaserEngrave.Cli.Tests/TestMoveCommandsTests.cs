using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Cli.Tests;

public class TestMoveCommandsTests
{
    private static string QrCode => Path.Combine(CliHarness.RepositoryRoot, "assets", "qr-code.bmp");

    private static long Microsteps(double mm) => JobGeometry.Round(StageUnits.MmToMicrosteps(mm, MachineProfile.Default.X.MicrostepUm));

    [Fact]
    public async Task GotoSimulate_Position_EndsThereWithTheLaserOff()
    {
        var (exit, output, error) = await CliHarness.RunAsync("goto", "1", "2", "--simulate");

        Assert.True(exit == 0, error);
        Assert.Equal($"at {Microsteps(1)}, {Microsteps(2)} microsteps = 1, 2 mm; laser off", output.TrimEnd());
    }

    [Fact]
    public async Task GotoSimulate_OutsideTheTravel_Exit2WithOneLine()
    {
        var (exit, _, error) = await CliHarness.RunAsync("goto", "100", "0", "--simulate");

        Assert.Equal(2, exit);
        Assert.Contains("X_MM 100: outside the travel 0..60 mm", error, StringComparison.Ordinal);
        Assert.Single(error.TrimEnd().Split('\n'));
    }

    [Fact]
    public async Task JogSimulate_XByMinus100Um_MovesXOnlyByTheStep()
    {
        // The simulated stage powers up at the far end of its travel on both axes.
        var travel = MachineProfile.Default.X.TravelMicrosteps;
        var step = JobGeometry.Round(StageUnits.UmToMicrosteps(100, MachineProfile.Default.X.MicrostepUm));

        var (exit, output, error) = await CliHarness.RunAsync("jog", "x", "-100", "--simulate");

        Assert.True(exit == 0, error);
        Assert.StartsWith($"at {travel - step}, {MachineProfile.Default.Y.TravelMicrosteps} microsteps", output, StringComparison.Ordinal);
    }

    [Fact]
    public async Task JogSimulate_PastTheEndOfTheTravel_Exit2WithOneLine()
    {
        var (exit, _, error) = await CliHarness.RunAsync("jog", "y", "100", "--simulate");

        Assert.Equal(2, exit);
        Assert.Contains("outside the stage travel", error, StringComparison.Ordinal);
        Assert.Single(error.TrimEnd().Split('\n'));
    }

    [Theory]
    [InlineData(new[] { "jog", "z", "100", "--simulate" }, "AXIS z")]
    [InlineData(new[] { "jog", "x", "0", "--simulate" }, "STEP_UM 0")]
    [InlineData(new[] { "fire", "--simulate" }, "give one of --pulses N or --ms T")]
    [InlineData(new[] { "fire", "--pulses", "5", "--ms", "10", "--simulate" }, "give one of --pulses N or --ms T")]
    [InlineData(new[] { "fire", "--pulses", "0", "--simulate" }, "--pulses 0")]
    [InlineData(new[] { "goto", "1", "2" }, "give the machine")]
    public async Task TestMove_BadInput_Exit2WithOneLine(string[] args, string expected)
    {
        var (exit, _, error) = await CliHarness.RunAsync(args);

        Assert.Equal(2, exit);
        Assert.Contains(expected, error, StringComparison.Ordinal);
        Assert.Single(error.TrimEnd().Split('\n'));
    }

    [Fact]
    public async Task FireSimulate_Pulses_FiresAndSwitchesOff()
    {
        var (exit, output, error) = await CliHarness.RunAsync("fire", "--pulses", "10", "--frequency-hz", "500", "--simulate");

        Assert.True(exit == 0, error);
        Assert.Equal("fired 10 pulses at 500 Hz; laser off", output.TrimEnd());
    }

    [Fact]
    public async Task FireSimulate_Milliseconds_FiresAndSwitchesOff()
    {
        var (exit, output, error) = await CliHarness.RunAsync("fire", "--ms", "50", "--simulate");

        Assert.True(exit == 0, error);
        Assert.Equal("fired for 50 ms at 1000 Hz; laser off", output.TrimEnd());
    }

    [Fact]
    public async Task FrameSimulate_QrCode_EndsAtTheJobsTopLeftCorner()
    {
        var (exit, output, error) = await CliHarness.RunAsync("frame", QrCode, "--width-mm", "5", "--origin-mm", "3,4", "--simulate");

        Assert.True(exit == 0, error);
        Assert.Equal($"at {Microsteps(3)}, {Microsteps(4)} microsteps = 3, 4 mm; laser off", output.TrimEnd());
    }

    [Fact]
    public async Task FrameSimulate_OutsideTheTravel_Exit2()
    {
        var (exit, _, error) = await CliHarness.RunAsync("frame", QrCode, "--width-mm", "20", "--origin-mm", "50,0", "--simulate");

        Assert.Equal(2, exit);
        Assert.Contains("does not fit the stage's travel", error, StringComparison.Ordinal);
        Assert.Single(error.TrimEnd().Split('\n'));
    }
}
