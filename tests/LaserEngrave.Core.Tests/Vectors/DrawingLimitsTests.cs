using System.Globalization;
using System.Text;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;
using static LaserEngrave.Core.Tests.Vectors.TestDrawings;

namespace LaserEngrave.Core.Tests.Vectors;

/// <summary>Each budget of reading and planning refuses a hostile drawing with one line naming the file and the limit.</summary>
public class DrawingLimitsTests
{
    private static string Line(double x0, double y0, double x1, double y1) => Entity("LINE", (8, "0"), (10, x0), (20, y0), (11, x1), (21, y1));

    private static string Insert(string block, int columns = 1, int rows = 1, double x = 0) =>
        Entity("INSERT", (8, "0"), (2, block), (10, x), (20, 0), (70, columns), (71, rows), (44, 0.01), (45, 0.01));

    private static string Block(string name, string body) => $"0\nBLOCK\n8\n0\n2\n{name}\n70\n0\n10\n0\n20\n0\n{body}0\nENDBLK\n";

    [Fact]
    public void Dxf_InsertArray32767Squared_RefusedAtOnceNamingTheInsert()
    {
        var dxf = Dxf(Insert("B", 32767, 32767), Block("B", Line(0, 0, 0.005, 0.005)));

        var ex = Assert.Throws<DrawingException>(() => DxfReader.Parse(dxf, "array.dxf"));

        Assert.StartsWith("array.dxf: INSERT (line ", ex.Message, StringComparison.Ordinal);
        Assert.Contains("arrays block \"B\" 32767 x 32767 times: more than 2 000 000 entities, the limit for a drawing", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Dxf_BlocksNested11DeepWith6InsertsEach_RefusedByThePathLimit()
    {
        var blocks = new StringBuilder(Block("B0", Line(0, 0, 0.001, 0.001)));
        for (var level = 1; level <= 11; level++)
        {
            blocks.Append(Block($"B{level}", string.Concat(Enumerable.Range(0, 6).Select(k => Insert($"B{level - 1}", x: k * 0.01)))));
        }

        var ex = Assert.Throws<DrawingException>(() => DxfReader.Parse(Dxf(Insert("B11"), blocks.ToString()), "nested.dxf"));

        Assert.Equal("nested.dxf: more than 500 000 paths (entities that draw), the limit for a drawing; split the drawing into files", ex.Message);
    }

    [Fact]
    public void Svg_Use4To15_RefusedByTheLimit()
    {
        var defs = new StringBuilder("<path id=\"u0\" d=\"M0 0 L0.001 0.001\"/>");
        for (var level = 1; level <= 15; level++)
        {
            defs.Append(CultureInfo.InvariantCulture, $"<g id=\"u{level}\">");
            for (var k = 0; k < 4; k++)
            {
                defs.Append(CultureInfo.InvariantCulture, $"<use href=\"#u{level - 1}\" x=\"{k * 0.001}\"/>");
            }

            defs.Append("</g>");
        }

        var ex = Assert.Throws<DrawingException>(() => SvgReader.Parse(Svg($"<defs>{defs}</defs><use href=\"#u15\"/>"), "use.svg"));

        Assert.StartsWith("use.svg: more than ", ex.Message, StringComparison.Ordinal);
        Assert.Contains("the limit for a drawing", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Svg_200000NestedGroups_RefusedBeforeTheTreeIsBuilt()
    {
        var svg = Svg(string.Concat(Enumerable.Repeat("<g>", 200_000)) + "<path d=\"M0 0 L1 1\"/>" + string.Concat(Enumerable.Repeat("</g>", 200_000)));

        var ex = Assert.Throws<DrawingException>(() => SvgReader.Parse(svg, "deep.svg"));

        Assert.Equal("deep.svg: line 2: more than 256 levels of nested elements, the limit for a drawing; flatten the groups in the drawing program", ex.Message);
    }

    [Fact]
    public void Svg_257NestedGroupsRefused_256Read()
    {
        string Nested(int depth) => Svg(string.Concat(Enumerable.Repeat("<g>", depth)) + "<path d=\"M0 0 L1 1\"/>" + string.Concat(Enumerable.Repeat("</g>", depth)));

        Assert.Single(SvgReader.Parse(Nested(254), "ok.svg").Paths);
        Assert.Throws<DrawingException>(() => SvgReader.Parse(Nested(300), "deep.svg"));
    }

    [Fact]
    public void Svg_MillionSubpaths_RefusedByThePathLimit()
    {
        var d = new StringBuilder();
        for (var i = 0; i < DrawingLimits.MaxPaths + 1; i++)
        {
            d.Append(CultureInfo.InvariantCulture, $"M{i % 1000} {i / 1000} l0.5 0.5 ");
        }

        var ex = Assert.Throws<DrawingException>(() => SvgReader.Parse(Svg($"<path d=\"{d}\"/>", 1000), "many.svg"));

        Assert.Equal("many.svg: more than 500 000 paths (subpaths and shapes), the limit for a drawing; split the drawing into files", ex.Message);
    }

    [Fact]
    public void Plan_CurvesFlattenedPastTheVertexLimit_RefusedNamingTheTolerance()
    {
        var circles = string.Concat(Enumerable.Range(0, 3000).Select(i => string.Create(CultureInfo.InvariantCulture, $"<circle cx=\"50\" cy=\"50\" r=\"{40 + (i * 0.001)}\"/>")));
        var drawing = SvgReader.Parse(Svg(circles), "circles.svg");

        var ex = Assert.Throws<DrawingException>(() => VectorPlanner.Plan(drawing, new VectorOptions { WidthMm = 60, ToleranceUm = 0.01 }, MachineProfile.Default));

        Assert.Equal("circles.svg: more than 10 000 000 vertices once its curves are flattened within 0.01 µm, the limit for a drawing; give a larger --tolerance-um or a smaller --width-mm", ex.Message);
    }

    [Fact]
    public void Prepare_PathsLongerThanTwelveHoursToBurn_RefusedBeforeTheMotionIsModelled()
    {
        var random = new Random(7);
        var points = string.Join(' ', Enumerable.Range(0, 2000).Select(_ => $"{random.Next(100)},{random.Next(100)}"));
        var path = Path.Combine(Path.GetTempPath(), $"le-long-{Guid.NewGuid():N}.svg");
        System.IO.File.WriteAllText(path, Svg($"<polyline points=\"{points}\"/>"));
        try
        {
            var spec = new JobSpec { ImagePath = path, Size = SizeSpec.Width(60) };

            var ex = Assert.Throws<DrawingException>(() => PreparedDrawing.Prepare(spec, new VectorOptions()));

            Assert.StartsWith($"{path}: its paths take ", ex.Message, StringComparison.Ordinal);
            Assert.Contains("h to burn at 1 mm/s, more than the 12 h a drawing job may take", ex.Message, StringComparison.Ordinal);
        }
        finally
        {
            System.IO.File.Delete(path);
        }
    }

    [Fact]
    public void Order_MoreThanTheExactScanLimit_EveryPathOnceAndHolesFirst()
    {
        // 2100 squares each with a smaller square inside: 4200 paths, above MaxTwoOptPaths, ordered through the grid.
        var paths = new List<StagePath>();
        for (var i = 0; i < 2100; i++)
        {
            long x = (i % 50) * 1000, y = (i / 50) * 1000;
            paths.Add(Square(x, y, 800));
            paths.Add(Square(x + 200, y + 200, 400));
        }

        var order = PathOrderer.Order(paths, new StagePoint(0, 0));

        Assert.Equal(paths.Count, order.Count);
        Assert.Equal(paths.Select(p => p.Source).Order(StringComparer.Ordinal), order.Select(p => p.Source).Order(StringComparer.Ordinal));
        var position = order.Select((p, k) => (p.Source, k)).ToDictionary(t => t.Source, t => t.k);
        for (var i = 0; i < 2100; i++)
        {
            Assert.True(position[paths[(2 * i) + 1].Source] < position[paths[2 * i].Source], $"hole {i} after its part");
        }

        // Nearest neighbour through the grid keeps the travel near the grid's own: about one cell per part.
        Assert.True(PathOrderer.Travel(order, new StagePoint(0, 0)) < 2100 * 2000);
    }

    private static StagePath Square(long x0, long y0, long s) =>
        new([new(x0, y0), new(x0 + s, y0), new(x0 + s, y0 + s), new(x0, y0 + s), new(x0, y0)], true, VectorPathKind.Outline, string.Empty, $"square at {x0},{y0},{s}");
}
