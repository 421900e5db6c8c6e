using LaserEngrave.Core.Vectors;
using static LaserEngrave.Core.Tests.Vectors.TestDrawings;

namespace LaserEngrave.Core.Tests.Vectors;

public class DxfReaderTests
{
    [Fact]
    public void Parse_Line_ReadsMillimetresWithYDown()
    {
        var drawing = DxfReader.Parse(Dxf(Entity("LINE", (5, "1A"), (8, "CUT"), (10, 1.5), (20, 2.5), (11, 4), (21, -3))), "t.dxf");

        var path = Assert.Single(drawing.Paths);
        Assert.Equal(new DrawingPoint(1.5, -2.5), path.Start);
        Assert.Equal(new DrawingPoint(4, 3), path.End);
        Assert.Equal("CUT", path.Layer);
        Assert.Contains("handle 1A", path.Source, StringComparison.Ordinal);
        Assert.True(drawing.UnitsStated);
    }

    [Theory]
    [InlineData(1, 25.4)]
    [InlineData(5, 10)]
    [InlineData(13, 0.001)]
    [InlineData(21, 304.80060960121924)]
    public void Parse_InsUnits_ScalesToMillimetres(int units, double mmPerUnit)
    {
        var drawing = DxfReader.Parse(Dxf(Entity("LINE", (10, 0), (20, 0), (11, 2), (21, 0)), insUnits: units), "t.dxf");

        Assert.Equal(2 * mmPerUnit, Assert.Single(drawing.Paths).End.X, 12);
    }

    [Fact]
    public void Parse_InsUnitsNotALength_ThrowsNamingIt()
    {
        var ex = Assert.Throws<DrawingException>(() => DxfReader.Parse(Dxf(Entity("LINE", (10, 0), (20, 0), (11, 2), (21, 0)), insUnits: 19), "ly.dxf"));

        Assert.Equal("ly.dxf: $INSUNITS 19 is not a unit of length LaserEngrave knows", ex.Message);
    }

    [Fact]
    public void Parse_NoInsUnits_WarnsAndReadsMillimetres()
    {
        var drawing = DxfReader.Parse(Dxf(Entity("LINE", (10, 0), (20, 0), (11, 2), (21, 0)), insUnits: null), "t.dxf");

        Assert.False(drawing.UnitsStated);
        Assert.Contains(drawing.Warnings, w => w.Contains("no units", StringComparison.Ordinal));
        Assert.Equal(2, drawing.Paths[0].End.X);
    }

    [Theory]
    [InlineData(1.0)]
    [InlineData(-1.0)]
    public void Parse_BulgeOfOne_IsHalfCircleOnTheSideItsSignSays(double bulge)
    {
        // Bulge +1 from (0,0) to (10,0) turns counter-clockwise (y up), through (5,-5); y down, that is (5,+5).
        var drawing = DxfReader.Parse(Dxf(LwPolyline(false, (0, 0, bulge), (10, 0, 0))), "t.dxf");

        var points = drawing.Paths[0].Flatten(1e-4);
        Assert.Equal(new DrawingPoint(0, 0), points[0]);
        Assert.Equal(new DrawingPoint(10, 0), points[^1]);
        Assert.All(points, p => Assert.InRange(Math.Sqrt(((p.X - 5) * (p.X - 5)) + (p.Y * p.Y)), 5 - 1e-4, 5 + 1e-9));
        Assert.All(points, p => Assert.True(p.Y * bulge >= -1e-12));
        Assert.Equal(5 * Math.PI, Length(points), 3);
    }

    [Fact]
    public void Parse_ArcStartAfterEnd_SweepsCounterClockwiseThroughZero()
    {
        var drawing = DxfReader.Parse(Dxf(Entity("ARC", (10, 0), (20, 0), (40, 10), (50, 350), (51, 10))), "t.dxf");

        // Chords within s of an arc of radius r are shorter than it by at most s / (3 r).
        var points = drawing.Paths[0].Flatten(1e-6);
        var exact = 10 * 20 * Math.PI / 180;
        Assert.InRange(Length(points), exact * (1 - (1e-6 / 30)), exact);
        Assert.All(points, p => Assert.True(p.X > 9.8));
    }

    [Fact]
    public void Parse_InsertScaledRotatedAndNested_PlacesBlocksByTheirTransforms()
    {
        // Block A: a line from its base point (1,0) to (2,0). Block B: A inserted at (0,0) rotated 90°.
        // The drawing inserts B at (10,5), scaled 2: A's line runs from (10,5) up to (10,7) (y up).
        var blocks =
            Entity("BLOCK", (2, "A"), (10, 1), (20, 0)) + Entity("LINE", (10, 1), (20, 0), (11, 2), (21, 0)) + Entity("ENDBLK") +
            Entity("BLOCK", (2, "B"), (10, 0), (20, 0)) + Entity("INSERT", (2, "A"), (10, 0), (20, 0), (50, 90)) + Entity("ENDBLK");
        var drawing = DxfReader.Parse(Dxf(Entity("INSERT", (5, "3C"), (2, "B"), (10, 10), (20, 5), (41, 2), (42, 2)), blocks), "t.dxf");

        var path = Assert.Single(drawing.Paths);
        Assert.Equal(10, path.Start.X, 12);
        Assert.Equal(-5, path.Start.Y, 12);
        Assert.Equal(10, path.End.X, 12);
        Assert.Equal(-7, path.End.Y, 12);
    }

    [Fact]
    public void Parse_MinsertArray_PlacesEveryCopy()
    {
        var blocks = Entity("BLOCK", (2, "DOT"), (10, 0), (20, 0)) + Entity("CIRCLE", (10, 0), (20, 0), (40, 1)) + Entity("ENDBLK");
        var drawing = DxfReader.Parse(Dxf(Entity("INSERT", (2, "DOT"), (10, 0), (20, 0), (70, 3), (71, 2), (44, 5), (45, 4)), blocks), "t.dxf");

        Assert.Equal(6, drawing.Paths.Count);
        Assert.Equal(6, drawing.Paths.Select(p => (Math.Round(p.Start.X, 9), Math.Round(p.Start.Y, 9))).Distinct().Count());
    }

    [Fact]
    public void Parse_Ellipse_PointsLieOnTheEllipseAndLengthMatchesIntegration()
    {
        var drawing = DxfReader.Parse(Dxf(Entity("ELLIPSE", (10, 0), (20, 0), (11, 10), (21, 0), (40, 0.5), (41, 0), (42, 2 * Math.PI))), "t.dxf");

        var points = drawing.Paths[0].Flatten(1e-3);
        Assert.True(drawing.Paths[0].Closed);
        Assert.All(points, p => Assert.Equal(1, Math.Pow(p.X / 10, 2) + Math.Pow(p.Y / 5, 2), 6));

        // The perimeter by the midpoint rule on the speed |(-10 sin t, 5 cos t)|.
        const int n = 200_000;
        var exact = Enumerable.Range(0, n).Sum(i =>
        {
            var t = (i + 0.5) * 2 * Math.PI / n;
            return Math.Sqrt(Math.Pow(10 * Math.Sin(t), 2) + Math.Pow(5 * Math.Cos(t), 2)) * 2 * Math.PI / n;
        });
        Assert.InRange(Length(points), exact * (1 - 1e-4), exact);
    }

    [Fact]
    public void Parse_ClampedCubicSpline_MatchesCoxDeBoorBasisEvaluation()
    {
        double[] knots = [0, 0, 0, 0, 1, 2, 3, 3, 3, 3];
        (double X, double Y)[] control = [(0, 0), (10, 20), (20, -10), (30, 15), (40, 0), (50, 10)];
        var groups = new List<(int, object)> { (5, "5A"), (70, 8), (71, 3), (72, knots.Length), (73, control.Length) };
        groups.AddRange(knots.Select(k => (40, (object)k)));
        foreach (var (x, y) in control)
        {
            groups.Add((10, x));
            groups.Add((20, y));
            groups.Add((30, 0));
        }

        var drawing = DxfReader.Parse(Dxf(Entity("SPLINE", [.. groups])), "t.dxf");

        // Independent evaluation: the B-spline basis by the Cox-de Boor recursion, y flipped as the reader does.
        var fine = Enumerable.Range(0, 100_001).Select(i =>
        {
            var u = Math.Min(3 * i / 100_000.0, 3 - 1e-12);
            double x = 0, y = 0;
            for (var j = 0; j < control.Length; j++)
            {
                var b = Basis(j, 3, u, knots);
                x += b * control[j].X;
                y += b * control[j].Y;
            }

            return new DrawingPoint(x, -y);
        }).ToList();
        var points = drawing.Paths[0].Flatten(1e-4);
        Assert.Equal(new DrawingPoint(0, 0), points[0]);
        Assert.Equal(50, points[^1].X, 9);
        Assert.Equal(-10, points[^1].Y, 9);
        Assert.InRange(Length(points), Length(fine) * (1 - 1e-5), Length(fine) * (1 + 1e-6));
    }

    [Fact]
    public void Parse_TextHatchAndPoint_WarnsWithCountsAndHandles()
    {
        var drawing = DxfReader.Parse(
            Dxf(Entity("TEXT", (5, "A1"), (1, "hello")) + Entity("TEXT", (5, "A2")) + Entity("HATCH", (5, "B1")) + Entity("POINT", (5, "C1"), (10, 0), (20, 0))
                + Entity("LINE", (10, 0), (20, 0), (11, 1), (21, 0))),
            "t.dxf");

        Assert.Single(drawing.Paths);
        Assert.Contains(drawing.Warnings, w => w.StartsWith("2 TEXT (handle A1, handle A2) skipped", StringComparison.Ordinal));
        Assert.Contains(drawing.Warnings, w => w.StartsWith("1 HATCH (handle B1) skipped", StringComparison.Ordinal));
        Assert.Contains(drawing.Warnings, w => w.StartsWith("1 POINT (handle C1) skipped", StringComparison.Ordinal));
    }

    [Fact]
    public void Read_BlocksDrawing_WarnsAboutTextHatchAndFrozenLayer()
    {
        var drawing = DxfReader.Read(File("blocks.dxf"));

        foreach (var expected in Expected("blocks.dxf").GetProperty("warnings").EnumerateArray())
        {
            Assert.Contains(drawing.Warnings, w => w.StartsWith(expected.GetString()!, StringComparison.Ordinal));
        }

        Assert.Equal(Expected("blocks.dxf").GetProperty("paths").GetInt32(), drawing.Paths.Count);
    }

    [Theory]
    [InlineData("LINE", "10\nabc\n20\n0\n", "\"abc\" on line")]
    [InlineData("INSERT", "2\nNOPE\n10\n0\n20\n0\n", "block \"NOPE\"")]
    [InlineData("CIRCLE", "10\n0\n20\n0\n40\n-1\n", "radius -1")]
    [InlineData("LWPOLYLINE", "90\n1\n10\n0\n20\n0\n", "at least 2")]
    public void Parse_BadEntity_ThrowsNamingFileEntityHandleAndProblem(string type, string body, string problem)
    {
        var text = Dxf($"0\n{type}\n5\n7F\n{body}");

        var ex = Assert.Throws<DrawingException>(() => DxfReader.Parse(text, "bad.dxf"));

        Assert.StartsWith($"bad.dxf: {type} (handle 7F, line ", ex.Message, StringComparison.Ordinal);
        Assert.Contains(problem, ex.Message, StringComparison.Ordinal);
        Assert.DoesNotContain('\n', ex.Message);
    }

    [Fact]
    public void Parse_BinaryOrNotDxf_ThrowsOneLine()
    {
        Assert.Contains("binary DXF", Assert.Throws<DrawingException>(() => DxfReader.Parse("AutoCAD Binary DXF\r\n\u001a\0", "b.dxf")).Message, StringComparison.Ordinal);
        Assert.Contains("not a DXF group code", Assert.Throws<DrawingException>(() => DxfReader.Parse("hello\nworld\n", "h.dxf")).Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Parse_CrLfBlankLinesAndLongLines_ReadsAsTheWholeFileSplitAtLineFeeds()
    {
        var line = Entity("LINE", (8, "CUT"), (10, 1), (20, 2), (11, 3), (21, 4));
        var plain = Dxf(line);

        // Carriage returns, blank lines at the end, a blank value in the middle, and a layer name longer than the reader's buffer.
        var longLayer = new string('L', 70_000);
        var crlf = plain.Replace("\n", "\r\n", StringComparison.Ordinal) + "\r\n  \n\n";
        var blankValue = Dxf(Entity("LINE", (1, ""), (8, "CUT"), (10, 1), (20, 2), (11, 3), (21, 4))) + "\n\n";
        var longName = Dxf(Entity("LINE", (8, longLayer), (10, 1), (20, 2), (11, 3), (21, 4)));

        var expected = DxfReader.Parse(plain, "t.dxf").Paths.Single();
        foreach (var text in new[] { crlf, blankValue, plain.TrimEnd('\n') })
        {
            var path = DxfReader.Parse(text, "t.dxf").Paths.Single();
            Assert.Equal(expected.Layer, path.Layer);
            Assert.Equal(expected.Curves.Count, path.Curves.Count);
        }

        Assert.Equal(longLayer, DxfReader.Parse(longName, "t.dxf").Paths.Single().Layer);
    }

    [Fact]
    public void Parse_ValueMissingAtTheEnd_NamesTheLastLine()
    {
        var text = Dxf(Entity("LINE", (10, 0), (20, 0), (11, 1), (21, 0))) + "999\n\n  \n";
        var lines = text.Split('\n').Length - 3;

        var ex = Assert.Throws<DrawingException>(() => DxfReader.Parse(text, "cut.dxf"));

        Assert.Equal($"cut.dxf: line {lines}: group code without a value (the file is cut short)", ex.Message);
    }

    [Fact]
    public void Parse_StructureErrorThenABadCodeFurtherOn_ReportsTheBadCode()
    {
        // An entity outside a BLOCK (a structure error) comes first; the line that is not a group code, after EOF, is
        // what the whole file read first reported, and still is.
        var text = "0\nSECTION\n2\nBLOCKS\n0\nLINE\n10\n0\n0\nENDSEC\n0\nEOF\nhello\nworld\n";

        var ex = Assert.Throws<DrawingException>(() => DxfReader.Parse(text, "s.dxf"));

        Assert.Equal("s.dxf: line 13: \"hello\" is not a DXF group code; is this an ASCII DXF file?", ex.Message);
        Assert.Contains("outside a BLOCK", Assert.Throws<DrawingException>(() => DxfReader.Parse(text[..^12], "s.dxf")).Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Parse_LayerTableAfterTheEntities_StillHidesTheFrozenLayer()
    {
        // The entities are converted as they are read; a TABLES section after them (not DXF's order) makes the reader
        // read the file again, keeping the entities until the layers are known.
        var entities = Entity("LINE", (8, "OFF"), (10, 0), (20, 0), (11, 1), (21, 0)) + Entity("LINE", (8, "ON"), (10, 0), (20, 1), (11, 1), (21, 1));
        var text = "0\nSECTION\n2\nENTITIES\n" + entities + "0\nENDSEC\n0\nSECTION\n2\nTABLES\n" + Entity("LAYER", (2, "OFF"), (70, 1)) + "0\nENDSEC\n0\nEOF\n";

        var drawing = DxfReader.Parse(text, "late.dxf");

        Assert.Equal("ON", drawing.Paths.Single().Layer);
        Assert.Contains(drawing.Warnings, w => w.Contains("off or frozen", StringComparison.Ordinal));
    }

    [Fact]
    public void Parse_BadEntityThenABadCodeFurtherOn_ReportsTheBadCode()
    {
        var text = Dxf(Entity("LINE", (10, "x"), (20, 0), (11, 1), (21, 0))).Replace("0\nEOF\n", "0\nEOF\nhello\nworld\n", StringComparison.Ordinal);

        var ex = Assert.Throws<DrawingException>(() => DxfReader.Parse(text, "b.dxf"));

        Assert.Contains("\"hello\" is not a DXF group code", ex.Message, StringComparison.Ordinal);
        Assert.Contains("\"x\" on line", Assert.Throws<DrawingException>(() => DxfReader.Parse(text.Replace("hello\nworld\n", string.Empty, StringComparison.Ordinal), "b.dxf")).Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Read_File_SameDrawingAsParsingItsText()
    {
        var text = Dxf(Entity("LINE", (8, "A"), (10, 0), (20, 0), (11, 5), (21, 0)) + Entity("CIRCLE", (8, "B"), (10, 1), (20, 1), (40, 2)));
        var file = Path.Combine(Path.GetTempPath(), $"dxf-{Guid.NewGuid():N}.dxf");
        System.IO.File.WriteAllText(file, text, new System.Text.UTF8Encoding(encoderShouldEmitUTF8Identifier: true));
        try
        {
            var read = DxfReader.Read(file);
            var parsed = DxfReader.Parse(text, file);

            Assert.Equal(parsed.Paths.Select(p => (p.Layer, p.Curves.Count)), read.Paths.Select(p => (p.Layer, p.Curves.Count)));
        }
        finally
        {
            System.IO.File.Delete(file);
        }
    }

    private static double Basis(int i, int p, double u, double[] k)
    {
        if (p == 0)
        {
            return k[i] <= u && u < k[i + 1] ? 1 : 0;
        }

        var left = k[i + p] == k[i] ? 0 : (u - k[i]) / (k[i + p] - k[i]) * Basis(i, p - 1, u, k);
        var right = k[i + p + 1] == k[i + 1] ? 0 : (k[i + p + 1] - u) / (k[i + p + 1] - k[i + 1]) * Basis(i + 1, p - 1, u, k);
        return left + right;
    }
}
