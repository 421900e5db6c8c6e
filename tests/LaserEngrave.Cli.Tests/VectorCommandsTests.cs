using System.Text.Json;

namespace LaserEngrave.Cli.Tests;

public class VectorCommandsTests
{
    private static string Drawing(string name) => Path.Combine(CliHarness.RepositoryRoot, "assets", "drawings", name);

    [Fact]
    public async Task PlanJson_ScatteredDrawing_ReportsLengthsAndTravelSavedOverHalf()
    {
        var (exit, output, _) = await CliHarness.RunAsync("plan", Drawing("scattered.dxf"), "--origin-mm", "5,5", "--json");

        Assert.Equal(0, exit);
        using var json = JsonDocument.Parse(output);
        var root = json.RootElement;
        foreach (var key in new[] { "burnLengthMm", "travelMm", "travelDrawingOrderMm", "travelSavedPercent", "pathCount", "warnings" })
        {
            Assert.True(root.TryGetProperty(key, out _), $"missing {key}");
        }

        double travel = root.GetProperty("travelMm").GetDouble(), drawn = root.GetProperty("travelDrawingOrderMm").GetDouble();
        Assert.Equal(100 * (drawn - travel) / drawn, root.GetProperty("travelSavedPercent").GetDouble(), 9);
        Assert.True(root.GetProperty("travelSavedPercent").GetDouble() >= 50);
        Assert.Equal(60, root.GetProperty("pathCount").GetInt32());
    }

    [Fact]
    public async Task PlanJson_WidthMm_ScalesTheDrawingAndItsLength()
    {
        using var own = JsonDocument.Parse((await CliHarness.RunAsync("plan", Drawing("hexagons.dxf"), "--json")).Out);
        using var scaled = JsonDocument.Parse((await CliHarness.RunAsync("plan", Drawing("hexagons.dxf"), "--width-mm", "10", "--json")).Out);

        var width = own.RootElement.GetProperty("widthMm").GetDouble();
        Assert.Equal(10, scaled.RootElement.GetProperty("widthMm").GetDouble(), 9);
        // Equal up to flattening: smaller circles lose a little more to their chords (s / (3 r)).
        var expected = own.RootElement.GetProperty("burnLengthMm").GetDouble() * 10 / width;
        Assert.InRange(scaled.RootElement.GetProperty("burnLengthMm").GetDouble(), expected * (1 - 1e-3), expected * (1 + 1e-6));
    }

    [Fact]
    public async Task Plan_SvgWithText_WarnsOnStderrNamingTheElement()
    {
        var (exit, output, error) = await CliHarness.RunAsync("plan", Drawing("every-command.svg"), "--width-mm", "40");

        Assert.Equal(0, exit);
        Assert.Contains("Burn length:", output, StringComparison.Ordinal);
        Assert.Contains("warning: 1 <text> (#label) skipped", error, StringComparison.Ordinal);
    }

    [Fact]
    public async Task PlanSegments_Drawing_WritesEveryBurnAndTravel()
    {
        var csv = CliHarness.TempFile(".csv");
        try
        {
            var (exit, output, _) = await CliHarness.RunAsync("plan", Drawing("hexagons.dxf"), "--json", "--segments", csv);

            Assert.Equal(0, exit);
            using var json = JsonDocument.Parse(output);
            var lines = await File.ReadAllLinesAsync(csv, TestContext.Current.CancellationToken);
            Assert.Equal("kind,x0,y0,x1,y1", lines[0]);
            var burn = lines.Skip(1).Where(l => l.StartsWith("burn,", StringComparison.Ordinal)).Sum(Length);
            Assert.Equal(json.RootElement.GetProperty("burnLengthMm").GetDouble(), burn * 0.09921875 / 1000, 6);
        }
        finally
        {
            File.Delete(csv);
        }

        static double Length(string line)
        {
            var v = line.Split(',').Skip(1).Select(long.Parse).ToArray();
            return Math.Sqrt(Math.Pow(v[2] - v[0], 2) + Math.Pow(v[3] - v[1], 2));
        }
    }

    [Fact]
    public async Task Preview_Drawing_WritesPng()
    {
        var png = CliHarness.TempFile(".png");
        try
        {
            var (exit, output, _) = await CliHarness.RunAsync("preview", Drawing("blocks.dxf"), "--out", png, "--max-px", "300", "--fill", "both");

            Assert.Equal(0, exit);
            Assert.Contains("paths", output, StringComparison.Ordinal);
            var bytes = await File.ReadAllBytesAsync(png, TestContext.Current.CancellationToken);
            Assert.Equal([0x89, (byte)'P', (byte)'N', (byte)'G'], bytes[..4]);
        }
        finally
        {
            File.Delete(png);
        }
    }

    [Fact]
    public async Task Plan_BadDrawing_Exit2WithOneLineNamingFileEntityAndProblem()
    {
        var dxf = CliHarness.TempFile(".dxf");
        try
        {
            await File.WriteAllTextAsync(dxf, "0\nSECTION\n2\nENTITIES\n0\nLINE\n5\n2A\n10\n1,5\n20\n0\n0\nENDSEC\n0\nEOF\n", TestContext.Current.CancellationToken);

            var (exit, _, error) = await CliHarness.RunAsync("plan", dxf);

            Assert.Equal(2, exit);
            Assert.Single(error.TrimEnd().Split('\n'));
            Assert.Contains($"{dxf}: LINE (handle 2A, line 6): \"1,5\" on line 10 is not a number", error, StringComparison.Ordinal);
        }
        finally
        {
            File.Delete(dxf);
        }
    }

    [Fact]
    public async Task EngraveJson_DrawingOnTheTwin_OnThePathEvenlySpacedAsEstimatedAndLogged()
    {
        var logs = Path.Combine(Path.GetTempPath(), $"le-cli-vector-{Guid.NewGuid():N}");
        try
        {
            var (exit, output, error) = await CliHarness.RunAsync("engrave", Drawing("hexagons.dxf"), "--width-mm", "8", "--origin-mm", "10,10", "--simulate", "--json", "--log-dir", logs);
            var (planExit, planOutput, _) = await CliHarness.RunAsync("plan", Drawing("hexagons.dxf"), "--width-mm", "8", "--origin-mm", "10,10", "--json");

            Assert.True(exit == 0, error);
            Assert.Equal(0, planExit);
            using var json = JsonDocument.Parse(output);
            using var plan = JsonDocument.Parse(planOutput);
            var root = json.RootElement;
            Assert.Equal("completed", root.GetProperty("outcome").GetString());
            Assert.InRange(root.GetProperty("pathDeviationUm").GetProperty("max").GetDouble(), 0, 3);
            var expected = root.GetProperty("expectedSpacingUm").GetDouble();
            Assert.InRange(root.GetProperty("pulseSpacingUm").GetProperty("min").GetDouble(), expected * 0.9, expected * 1.1);
            Assert.InRange(root.GetProperty("pulseSpacingUm").GetProperty("max").GetDouble(), expected * 0.9, expected * 1.1);
            Assert.Equal(0, root.GetProperty("laserOnTravelCount").GetInt64());
            Assert.Equal(0, root.GetProperty("dwells").GetProperty("count").GetInt32());

            // The plan's estimate is the run's, and within 2 % of what the twin took.
            var estimate = plan.RootElement.GetProperty("estimatedEngravingSeconds").GetDouble();
            Assert.Equal(estimate, root.GetProperty("estimatedEngravingSeconds").GetDouble(), 9);
            Assert.InRange(root.GetProperty("engravingSeconds").GetDouble(), estimate * 0.98, estimate * 1.02);
            var whole = plan.RootElement.GetProperty("estimatedSeconds").GetDouble();
            Assert.InRange(root.GetProperty("durationSeconds").GetDouble(), whole * 0.98, whole * 1.02);

            using var log = JsonDocument.Parse(File.ReadAllText(root.GetProperty("logPath").GetString()!));
            Assert.Equal(plan.RootElement.GetProperty("pathCount").GetInt32(), log.RootElement.GetProperty("drawing").GetProperty("paths").GetInt32());
            Assert.True(log.RootElement.GetProperty("simulation").GetProperty("path").GetProperty("deviationUm").GetProperty("max").GetDouble() <= 3);
        }
        finally
        {
            if (Directory.Exists(logs))
            {
                Directory.Delete(logs, recursive: true);
            }
        }
    }

    [Fact]
    public async Task Engrave_DrawingWithAPathTooShortToBurn_DoneWithEveryPathItBurnsAndLoggedSo()
    {
        // Issue 23: the 3 µm line is not burned; the run counted it as a path to do and ended "stopped: 2 of 3 paths".
        var folder = Path.Combine(Path.GetTempPath(), $"le-cli-vector-{Guid.NewGuid():N}");
        Directory.CreateDirectory(folder);
        try
        {
            var svg = Path.Combine(folder, "short.svg");
            File.WriteAllText(svg, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10mm\" height=\"10mm\" viewBox=\"0 0 10 10\"><line x1=\"1\" y1=\"1\" x2=\"1.003\" y2=\"1\"/><line x1=\"2\" y1=\"2\" x2=\"4\" y2=\"2\"/><line x1=\"2\" y1=\"4\" x2=\"4\" y2=\"4\"/></svg>");
            var (exit, output, error) = await CliHarness.RunAsync("engrave", svg, "--origin-mm", "5,5", "--simulate", "--log-dir", folder);

            Assert.True(exit == 0, error);
            Assert.Contains("done: 100 %, stroke 2 of 2, 2 of 2 paths", error, StringComparison.Ordinal);
            Assert.Contains("Done:             2 of 2 strokes, 2 of 2 paths", output, StringComparison.Ordinal);
            using var log = JsonDocument.Parse(File.ReadAllText(Directory.GetFiles(folder, "*.json", SearchOption.AllDirectories).Single()));
            Assert.Equal(3, log.RootElement.GetProperty("drawing").GetProperty("paths").GetInt32());
            Assert.Equal((2, 2), (log.RootElement.GetProperty("runsDone").GetInt64(), log.RootElement.GetProperty("runsTotal").GetInt64()));
        }
        finally
        {
            Directory.Delete(folder, recursive: true);
        }
    }

    [Fact]
    public async Task EngraveFromLog_Drawing_RepeatsTheSameStrokes()
    {
        var logs = Path.Combine(Path.GetTempPath(), $"le-cli-vector-{Guid.NewGuid():N}");
        try
        {
            var (exit, output, _) = await CliHarness.RunAsync("engrave", Drawing("curves-r12.dxf"), "--width-mm", "6", "--origin-mm", "3,3", "--tolerance-um", "2", "--simulate", "--json", "--log-dir", logs);
            using var first = JsonDocument.Parse(output);
            var logPath = first.RootElement.GetProperty("logPath").GetString()!;
            var (again, repeated, error) = await CliHarness.RunAsync("engrave", "--from-log", logPath, "--simulate", "--json", "--log-dir", logs);

            Assert.Equal(0, exit);
            Assert.True(again == 0, error);
            using var second = JsonDocument.Parse(repeated);
            Assert.Equal(first.RootElement.GetProperty("estimatedSeconds").GetDouble(), second.RootElement.GetProperty("estimatedSeconds").GetDouble(), 9);
            Assert.Equal(first.RootElement.GetProperty("rowsTotal").GetInt32(), second.RootElement.GetProperty("rowsTotal").GetInt32());
        }
        finally
        {
            if (Directory.Exists(logs))
            {
                Directory.Delete(logs, recursive: true);
            }
        }
    }

    [Theory]
    [InlineData(new[] { "--origin-mm", "59,10" }, "does not fit the stage's travel")]
    [InlineData(new[] { "--burned", "b.png" }, "--burned and --dose are for images")]
    [InlineData(new[] { "--threshold", "40" }, "--threshold is for images")]
    public async Task Engrave_DrawingWithBadOptions_Exit2OneLineBeforeAnythingOpens(string[] options, string expected)
    {
        var (exit, _, error) = await CliHarness.RunAsync(["engrave", Drawing("hexagons.dxf"), "--width-mm", "20", "--simulate", "--log-dir", Path.Combine(Path.GetTempPath(), "le-never"), .. options]);

        Assert.Equal(2, exit);
        Assert.Contains(expected, error, StringComparison.Ordinal);
        Assert.Single(error.TrimEnd().Split('\n'));
        Assert.False(Directory.Exists(Path.Combine(Path.GetTempPath(), "le-never")));
    }

    [Fact]
    public async Task Frame_Drawing_TracesItsBoundingBoxAndStopsAtTheTopLeft()
    {
        var (exit, output, error) = await CliHarness.RunAsync("frame", Drawing("hexagons.dxf"), "--width-mm", "20", "--origin-mm", "10,10", "--simulate");

        Assert.True(exit == 0, error);
        Assert.Contains("= 10, 10 mm", output, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData(new[] { "--height-mm", "5" }, "sized by --width-mm")]
    [InlineData(new[] { "--fill", "hatch" }, "--fill hatch")]
    [InlineData(new[] { "--tolerance-um", "0" }, "--tolerance-um")]
    [InlineData(new[] { "--width-mm", "-3" }, "--width-mm -3")]
    public async Task Plan_DrawingWithBadOptions_Exit2WithOneLine(string[] options, string expected)
    {
        var (exit, _, error) = await CliHarness.RunAsync(["plan", Drawing("hexagons.dxf"), .. options]);

        Assert.Equal(2, exit);
        Assert.Contains(expected, error, StringComparison.Ordinal);
        Assert.Single(error.TrimEnd().Split('\n'));
    }

    [Fact]
    public async Task EngraveJob_LayersOnTheTwin_RunInOrderEachWithItsSettingsAndLoggedPerLayer()
    {
        var job = Path.Combine(CliHarness.RepositoryRoot, "assets", "jobs", "plate.json");
        var logs = Path.Combine(Path.GetTempPath(), $"le-cli-layers-{Guid.NewGuid():N}");
        try
        {
            var (planExit, planOutput, _) = await CliHarness.RunAsync("plan", "--job", job, "--json");
            var (exit, output, error) = await CliHarness.RunAsync("engrave", "--job", job, "--simulate", "--json", "--log-dir", logs);

            Assert.Equal(0, planExit);
            Assert.True(exit == 0, error);
            using var plan = JsonDocument.Parse(planOutput);
            using var run = JsonDocument.Parse(output);
            var estimate = plan.RootElement.GetProperty("estimatedEngravingSeconds").GetDouble();
            Assert.Equal(estimate, run.RootElement.GetProperty("estimatedEngravingSeconds").GetDouble(), 6);
            Assert.InRange(run.RootElement.GetProperty("engravingSeconds").GetDouble(), estimate * 0.98, estimate * 1.02);

            using var log = JsonDocument.Parse(File.ReadAllText(run.RootElement.GetProperty("logPath").GetString()!));
            var layers = log.RootElement.GetProperty("layers").EnumerateArray().ToList();
            Assert.Equal(["marks", "logo", "cut"], layers.Select(l => l.GetProperty("name").GetString()));
            Assert.All(layers, l => Assert.Equal("completed", l.GetProperty("outcome").GetString()));
            Assert.Equal(0.5, layers[0].GetProperty("burnSpeedMmPerS").GetDouble());
            Assert.Equal(500, layers[0].GetProperty("frequencyHz").GetDouble());
            Assert.Equal(2, layers[2].GetProperty("passesDone").GetInt32());
            Assert.Equal("raster", layers[1].GetProperty("mode").GetString());
            Assert.Equal(0, layers[1].GetProperty("simulation").GetProperty("missingPixels").GetInt64());
            Assert.True(layers[0].GetProperty("simulation").GetProperty("path").GetProperty("deviationUm").GetProperty("max").GetDouble() <= 3);
            Assert.True(layers[2].GetProperty("simulation").GetProperty("path").GetProperty("deviationUm").GetProperty("max").GetDouble() <= 3);
        }
        finally
        {
            if (Directory.Exists(logs))
            {
                Directory.Delete(logs, recursive: true);
            }
        }
    }

    [Theory]
    [InlineData(new[] { "--width-mm", "5" }, "--width-mm with --job")]
    [InlineData(new[] { "--passes", "2" }, "--passes with --job: each layer has its own passes")]
    public async Task EngraveJob_WithTheJobsOwnOptions_Exit2OneLine(string[] options, string expected)
    {
        var job = Path.Combine(CliHarness.RepositoryRoot, "assets", "jobs", "plate.json");

        var (exit, _, error) = await CliHarness.RunAsync(["engrave", "--job", job, "--simulate", .. options]);

        Assert.Equal(2, exit);
        Assert.Contains(expected, error, StringComparison.Ordinal);
        Assert.Single(error.TrimEnd().Split('\n'));
    }
}
