using System.Text.Json;

namespace LaserEngrave.Cli.Tests;

public sealed class SweepCommandTests : IDisposable
{
    private readonly string folder = Path.Combine(Path.GetTempPath(), $"le-cli-sweep-{Guid.NewGuid():N}");

    public SweepCommandTests() => Directory.CreateDirectory(folder);

    [Fact]
    public async Task Sweep_CellsThisComputerCannotHoldOnAGateWithoutAfter_Exit2NamingThemBeforeAnythingOpensNoLog()
    {
        // Issue 34: the 10 x 10 grid failed 25 minutes in at its 3.6-4 mm/s rows; on a gate that cannot time its switch-ons
        // those cells are named before the first one burns.
        var options = Path.Combine(folder, "no-after.json");
        await File.WriteAllTextAsync(options, """{ "gateScheduledBursts": false }""", TestContext.Current.CancellationToken);
        var logs = Path.Combine(folder, "logs");

        var (exit, _, error) = await CliHarness.RunAsync(
            "sweep", "--rows", "speed=0.4,0.8,1.2,1.6,2,2.4,2.8,3.2,3.6,4", "--columns", "frequency=500,1000,1500,2000,2500,3000,3500,4000,4500,5000",
            "--origin-mm", "5,5", "--simulate", "--sim-options", options, "--log-dir", logs);

        Assert.Equal(2, exit);
        var line = Assert.Single(error.Split('\n', StringSplitOptions.RemoveEmptyEntries), l => l.StartsWith("laserengrave: ", StringComparison.Ordinal));
        Assert.StartsWith("laserengrave: 30 cells of the sweep (every cell at 3.2, 3.6, 4 mm/s) burn faster than this computer can hold with this gate: ", line, StringComparison.Ordinal);
        Assert.Contains("the fastest it holds is 3 mm/s: sweep speeds up to that", line, StringComparison.Ordinal);
        Assert.False(Directory.Exists(logs) && Directory.EnumerateFiles(logs).Any());
    }

    [Fact]
    public async Task SweepPlanOnly_Json_EveryCellWithItsValuesPlaceAndPulses()
    {
        var (exit, output, error) = await CliHarness.RunAsync(
            "sweep", "--rows", "speed=0.5,1", "--columns", "frequency=500,1000,2000", "--origin-mm", "5,5", "--plan-only", "--json");

        Assert.True(exit == 0, error);
        using var json = JsonDocument.Parse(output);
        var cells = json.RootElement.GetProperty("cells");
        Assert.Equal(6, cells.GetArrayLength());
        var last = cells[5];
        Assert.Equal(1, last.GetProperty("parameters").GetProperty("speedMmPerS").GetDouble());
        Assert.Equal(2000, last.GetProperty("parameters").GetProperty("frequencyHz").GetDouble());

        // Third column, second row: 2 x 1.5 mm and 1.5 mm from the corner; 50 µm x 2000 Hz / 1 mm/s = 100 pulses a pixel.
        Assert.Equal((8.0, 6.5), (last.GetProperty("originXMm").GetDouble(), last.GetProperty("originYMm").GetDouble()));
        Assert.Equal(100, last.GetProperty("pulsesPerPixel").GetDouble(), 9);
    }

    [Fact]
    public async Task SweepSimulate_TwoByTwoWithLabels_Exit0OneSweepLogDoseMapsPerCell()
    {
        var logs = Path.Combine(folder, "logs");
        var doses = Path.Combine(folder, "dose");

        var (exit, output, error) = await CliHarness.RunAsync(
            "sweep", "--rows", "speed=1,2", "--columns", "passes=1,2", "--cell-mm", "0.4", "--labels", "--origin-mm", "5,5",
            "--simulate", "--json", "--log-dir", logs, "--dose-dir", doses);

        Assert.True(exit == 0, error);
        using var json = JsonDocument.Parse(output);
        var root = json.RootElement;
        Assert.Equal("completed", root.GetProperty("outcome").GetString());
        Assert.EndsWith(".sweep.json", root.GetProperty("logPath").GetString(), StringComparison.Ordinal);
        var cells = root.GetProperty("sweep").GetProperty("cells");
        Assert.Equal(4, cells.GetArrayLength());

        // Two passes burn twice the pulses of one: 50 µm / 1 µm = 50, then 100 a pixel at 1 mm/s.
        var one = cells[0].GetProperty("run").GetProperty("simulation").GetProperty("pulsesPerPixel").GetProperty("mean").GetDouble();
        var two = cells[1].GetProperty("run").GetProperty("simulation").GetProperty("pulsesPerPixel").GetProperty("mean").GetDouble();
        Assert.InRange(one, 49, 51);
        Assert.InRange(two, 98, 102);
        Assert.Equal(4, Directory.GetFiles(doses, "cell-r*-c*.png").Length);
        Assert.Contains("4 of 5", error, StringComparison.Ordinal);
    }

    [Fact]
    public async Task FocusSeriesSimulate_ThreeAxisProfile_ZAtEachFocusWhileFiringSmallestSpotAtTheTrueFocus()
    {
        var options = Path.Combine(folder, "sim.json");
        await File.WriteAllTextAsync(options, """{ "trueFocusOffsetUm": 60, "rayleighLengthUm": 100 }""", TestContext.Current.CancellationToken);
        var profile = Path.Combine(CliHarness.RepositoryRoot, "assets", "profiles", "three-axis.json");

        var (exit, output, error) = await CliHarness.RunAsync(
            "focus-series", "--focus-um", "-100..100:50", "--cell-mm", "0.2", "--pitch-um", "40", "--labels", "--profile", profile,
            "--simulate", "--sim-options", options, "--json", "--log-dir", Path.Combine(folder, "logs"));

        Assert.True(exit == 0, error);
        using var json = JsonDocument.Parse(output);
        var cells = json.RootElement.GetProperty("sweep").GetProperty("cells");
        Assert.Equal(5, cells.GetArrayLength());
        var microstepUm = 0.09921875;
        var spots = new List<double>();
        foreach (var cell in cells.EnumerateArray())
        {
            // Visible focus 12.5 mm + the cell's offset, in microsteps rounded once; the twin's Z stood there whenever the laser fired.
            var offset = cell.GetProperty("parameters").GetProperty("focusUm").GetDouble();
            var expected = (long)Math.Round(((12.5 * 1000) + offset) / microstepUm);
            Assert.Equal(expected, cell.GetProperty("focusZMicrosteps").GetInt64());
            Assert.Equal(expected, cell.GetProperty("zReachedMicrosteps").GetInt64());
            var focus = cell.GetProperty("run").GetProperty("simulation").GetProperty("focus");
            Assert.Equal((expected, expected), (focus.GetProperty("zMinMicrosteps").GetInt64(), focus.GetProperty("zMaxMicrosteps").GetInt64()));
            Assert.Equal(0, focus.GetProperty("laserOnWhileZMoving").GetInt32());
            spots.Add(focus.GetProperty("spotDiameterUm").GetDouble());
        }

        // The true focus 60 µm above the visible one: the +50 µm cell (4th) has the smallest spot, 20 µm x √(1 + (10/100)²).
        Assert.Equal(3, spots.IndexOf(spots.Min()));
        Assert.Equal(20 * Math.Sqrt(1 + (0.1 * 0.1)), spots[3], 1);
    }

    [Fact]
    public async Task SweepPlanOnly_ImagePattern_EachCellTheImageItsLargerSideTheCell()
    {
        var qr = Path.Combine(CliHarness.RepositoryRoot, "assets", "qr-code.bmp");

        var (exit, output, error) = await CliHarness.RunAsync(
            "sweep", "--rows", "speed=0.5,1", "--pattern", "image", "--cell-image", qr, "--cell-mm", "2", "--plan-only", "--json");

        Assert.True(exit == 0, error);
        using var json = JsonDocument.Parse(output);
        var cell = json.RootElement.GetProperty("cells")[1];

        // The QR code is 41 x 41 px: 2 mm / 41 = 48.78 µm a pixel.
        Assert.Equal(2000.0 / 41, cell.GetProperty("pitchUm").GetDouble(), 6);
        Assert.Equal(2, cell.GetProperty("sizeMm").GetDouble(), 3);
    }

    public void Dispose()
    {
        if (Directory.Exists(folder))
        {
            Directory.Delete(folder, recursive: true);
        }
    }
}
