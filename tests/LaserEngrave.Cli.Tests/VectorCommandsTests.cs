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
    public async Task Engrave_Drawing_Exit2SayingDrawingsAreNotEngravedYet()
    {
        var (exit, _, error) = await CliHarness.RunAsync("engrave", Drawing("hexagons.dxf"), "--width-mm", "5", "--simulate");

        Assert.Equal(2, exit);
        Assert.Contains("hexagons.dxf: drawings can be planned and previewed", error, StringComparison.Ordinal);
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
}
