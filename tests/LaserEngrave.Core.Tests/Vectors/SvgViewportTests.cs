using System.Text.Json;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Tests.Vectors;

/// <summary>A used symbol and a nested svg placed and scaled as the SVG specification says, as Chromium draws them (issue 32, finding 9).</summary>
public class SvgViewportTests
{
    private const double MmPerPx = 25.4 / 96;

    public static TheoryData<string> Files =>
    [
        .. Directory.GetFiles(Path.Combine(TestDrawings.Folder, "symbols"), "*.svg").Select(f => Path.GetFileName(f)).Order(StringComparer.Ordinal),
    ];

    /// <summary>The box of the dark pixels in Chromium's screenshot of the file, px (tools/svg-chromium-boxes.py).</summary>
    private static double[] ChromiumBox(string name)
    {
        using var json = JsonDocument.Parse(File.ReadAllText(Path.Combine(TestDrawings.Folder, "symbols", "chromium-boxes.json")));
        return [.. json.RootElement.GetProperty(name).EnumerateArray().Select(v => v.GetDouble())];
    }

    [Theory]
    [MemberData(nameof(Files))]
    public void Read_SymbolOrNestedSvg_SameBoxAsChromiumDraws(string name)
    {
        var drawing = SvgReader.Read(Path.Combine(TestDrawings.Folder, "symbols", name));

        var (min, max) = drawing.Bounds();
        var box = ChromiumBox(name);
        double[] read = [min.X / MmPerPx, min.Y / MmPerPx, max.X / MmPerPx, max.Y / MmPerPx];
        for (var i = 0; i < 4; i++)
        {
            Assert.True(Math.Abs(read[i] - box[i]) <= 0.75, $"{name}: read [{string.Join(", ", read.Select(v => v.ToString("0.##", System.Globalization.CultureInfo.InvariantCulture)))}] px, Chromium drew [{string.Join(", ", box)}]");
        }

        Assert.DoesNotContain(drawing.Warnings, w => w.Contains("viewBox", StringComparison.Ordinal) || w.Contains("clips", StringComparison.Ordinal));
    }

    [Fact]
    public void Read_SymbolUsed20MmWide_20MmWide()
    {
        var drawing = SvgReader.Parse(
            """<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100"><defs><symbol id="s" viewBox="0 0 10 10"><rect width="10" height="10"/></symbol></defs><use href="#s" x="5" y="5" width="20" height="20"/></svg>""",
            "t.svg");

        var (min, max) = drawing.Bounds();

        Assert.Equal((5, 5, 25, 25), (Math.Round(min.X, 9), Math.Round(min.Y, 9), Math.Round(max.X, 9), Math.Round(max.Y, 9)));
    }

    [Fact]
    public void Read_SymbolContentOutsideItsViewport_EngravedWithAWarning()
    {
        var drawing = SvgReader.Parse(
            """<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100"><defs><symbol id="s"><rect x="5" y="5" width="30" height="20"/></symbol></defs><use href="#s" x="50" y="60" width="10" height="10"/></svg>""",
            "t.svg");

        var (_, max) = drawing.Bounds();

        Assert.Equal(85, max.X, 9);
        Assert.Contains(drawing.Warnings, w => w.Contains("<use>", StringComparison.Ordinal) && w.EndsWith("which a browser clips; they are engraved unclipped", StringComparison.Ordinal));
    }
}
