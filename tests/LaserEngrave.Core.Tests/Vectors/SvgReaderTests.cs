using LaserEngrave.Core.Vectors;
using static LaserEngrave.Core.Tests.Vectors.TestDrawings;

namespace LaserEngrave.Core.Tests.Vectors;

public class SvgReaderTests
{
    private static Drawing Parse(string body, double size = 100) => SvgReader.Parse(Svg(body, size), "t.svg");

    private static List<DrawingPoint> Points(DrawingPath path) => path.Flatten(1e-6);

    [Theory]
    [InlineData(".hide { display: none }", "<path class=\"hide\" d=\"M0 0 L5 5\"/><path d=\"M0 10 L5 15\"/>", 1)]
    [InlineData("path { visibility: hidden } #shown { visibility: visible }", "<path d=\"M0 0 L5 5\"/><path id=\"shown\" d=\"M0 10 L5 15\"/>", 1)]
    [InlineData("g.off, line { display:none !important; stroke: red }", "<g class=\"off other\"><path d=\"M0 0 L5 5\"/></g><line x1=\"0\" y1=\"0\" x2=\"1\" y2=\"1\"/><path d=\"M0 10 L5 15\"/>", 1)]
    [InlineData(".a { display: none } .a.b { display: inline }", "<path class=\"a b\" d=\"M0 0 L5 5\"/><path class=\"a\" d=\"M0 10 L5 15\"/>", 1)]
    [InlineData(".hide { display: none }", "<path class=\"hide\" style=\"display: inline\" d=\"M0 0 L5 5\"/>", 1)]
    [InlineData("/* .x { display: none } */ path { stroke: blue; fill: none }", "<path class=\"x\" d=\"M0 0 L5 5\"/>", 1)]
    [InlineData("#gone { display: none }", "<path id=\"gone\" display=\"inline\" d=\"M0 0 L5 5\"/><path d=\"M0 10 L5 15\"/>", 1)]
    public void Parse_StyleSheetRules_HideWhatTheDrawingHides(string css, string body, int drawn)
    {
        var drawing = Parse($"<style>{css}</style>{body}");

        Assert.Equal(drawn, drawing.Paths.Count);
    }

    [Theory]
    [InlineData("g .hide { display: none }", "\"g .hide { display: none }\" cannot be applied")]
    [InlineData("g > path { visibility: hidden }", "\"g > path { visibility: hidden }\" cannot be applied")]
    [InlineData("path[d] { display: none }", "\"path[d] { display: none }\" cannot be applied")]
    [InlineData("path:hover, .x { display: none }", "\"path:hover { display: none }\" cannot be applied")]
    [InlineData("@media print { .x { display: none } }", "at-rules (@media, @import, @supports) are not applied")]
    public void Parse_StyleRuleItCannotApply_RefusedNamingTheRule(string css, string fragment)
    {
        var ex = Assert.Throws<DrawingException>(() => Parse($"<style>{css}</style><path d=\"M0 0 L5 5\"/>"));

        Assert.StartsWith("t.svg: <style> (line 2): ", ex.Message, StringComparison.Ordinal);
        Assert.Contains(fragment, ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Parse_ComplexSelectorSettingOnlyStroke_ReadPast()
    {
        var drawing = Parse("<style>g > path:hover { stroke: red; stroke-width: 2 }</style><path d=\"M0 0 L5 5\"/>");

        Assert.Single(drawing.Paths);
    }

    [Theory]
    [InlineData("<g transform=\"scale(1e308)\"><path d=\"M0 0 L5 5 L5 0 Z\"/></g>", "infinity")]
    [InlineData("<path d=\"M0 0 L1e308 5\"/>", "1e+308")]
    [InlineData("<path transform=\"translate(2e7)\" d=\"M0 0 L5 5\"/>", "2e+07")]
    public void Bounds_CoordinatePastTheLimit_RefusedNotNaN(string body, string shown)
    {
        var drawing = Parse(body);

        var ex = Assert.Throws<DrawingException>(() => drawing.Bounds());

        Assert.StartsWith($"t.svg: a coordinate of {shown} mm is beyond the drawing limit", ex.Message, StringComparison.OrdinalIgnoreCase);
    }

    [Fact]
    public void Parse_ViewBoxAndWidthInMm_MapsUserUnitsToMillimetres()
    {
        var drawing = SvgReader.Parse(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10cm\" height=\"50mm\" viewBox=\"-10 0 200 100\"><line x1=\"-10\" y1=\"0\" x2=\"190\" y2=\"100\"/></svg>",
            "t.svg");

        Assert.True(drawing.UnitsStated);
        Assert.Equal(0, drawing.Paths[0].Start.X, 12);
        Assert.Equal(0, drawing.Paths[0].Start.Y, 12);
        Assert.Equal(100, drawing.Paths[0].End.X, 12);
        Assert.Equal(50, drawing.Paths[0].End.Y, 12);
    }

    [Fact]
    public void Parse_ViewBoxOfOtherAspect_MeetsAndCentres()
    {
        // 100 x 100 mm showing a 200 x 100 box: 0.5 mm per unit, centred vertically (25 mm above and below).
        var drawing = SvgReader.Parse(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100mm\" height=\"100mm\" viewBox=\"0 0 200 100\"><line x1=\"0\" y1=\"0\" x2=\"200\" y2=\"100\"/></svg>",
            "t.svg");

        Assert.Equal(new DrawingPoint(0, 25), drawing.Paths[0].Start);
        Assert.Equal(new DrawingPoint(100, 75), drawing.Paths[0].End);
    }

    [Fact]
    public void Parse_NoPhysicalUnits_Reads96PixelsPerInchAndWarns()
    {
        var drawing = SvgReader.Parse("<svg xmlns=\"http://www.w3.org/2000/svg\"><line x1=\"0\" y1=\"0\" x2=\"96\" y2=\"0\"/><circle cx=\"0\" cy=\"0\" r=\"1in\"/></svg>", "t.svg");

        Assert.False(drawing.UnitsStated);
        Assert.Contains(drawing.Warnings, w => w.Contains("96 per inch", StringComparison.Ordinal));
        Assert.Equal(25.4, drawing.Paths[0].End.X, 12);
        Assert.Equal(25.4, drawing.Paths[1].Start.X, 12);
    }

    [Theory]
    [InlineData("M10 10 L20 10 L20 20 L10 20 Z")]
    [InlineData("m10 10 l10 0 l0 10 l-10 0 z")]
    [InlineData("M10 10 20 10 20 20 10 20 z")]
    [InlineData("m10,10 10,0 0,10 -10,0z")]
    [InlineData("M10 10 H20 V20 H10 Z")]
    [InlineData("M10 10 h10 v10 h-10 Z")]
    [InlineData("M 1e1,1e1 h+1E1 v.1e2 h-10z")]
    public void Parse_LineCommands_AbsoluteRelativeAndImplicit_DrawTheSameSquare(string d)
    {
        var drawing = Parse($"<path d=\"{d}\"/>");

        var path = Assert.Single(drawing.Paths);
        Assert.True(path.Closed);
        Assert.Equal([new(10, 10), new(20, 10), new(20, 20), new(10, 20), new(10, 10)], Points(path));
    }

    [Fact]
    public void Parse_SmoothCurves_ReflectTheLastControlPoint()
    {
        // S after C mirrors C's second control point; T after Q mirrors Q's control point.
        var smooth = Parse("<path d=\"M0 0 C10 -10 20 -10 30 0 S50 10 60 0 Q70 -10 80 0 T100 0\"/>");
        var spelled = Parse("<path d=\"M0 0 C10 -10 20 -10 30 0 C40 10 50 10 60 0 Q70 -10 80 0 Q90 10 100 0\"/>");

        Assert.Equal(Points(spelled.Paths[0]), Points(smooth.Paths[0]));
    }

    [Fact]
    public void Parse_CubicBezier_PointsMatchTheBernsteinForm()
    {
        var drawing = Parse("<path d=\"M0 0 c10 -20 30 -20 40 0\"/>");

        var points = Points(drawing.Paths[0]);
        Assert.True(points.Count > 10);

        // Every vertex is on the curve: it solves x(t) for t and compares y(t).
        foreach (var p in points)
        {
            double lo = 0, hi = 1;
            for (var i = 0; i < 80; i++)
            {
                var mid = (lo + hi) / 2;
                if (X(mid) < p.X)
                {
                    lo = mid;
                }
                else
                {
                    hi = mid;
                }
            }

            Assert.True(Math.Abs(Y(lo) - p.Y) < 1e-9, $"{p} is off the curve");
        }

        static double X(double t) => (3 * (1 - t) * (1 - t) * t * 10) + (3 * (1 - t) * t * t * 30) + (t * t * t * 40);

        static double Y(double t) => (3 * (1 - t) * (1 - t) * t * -20) + (3 * (1 - t) * t * t * -20);
    }

    [Theory]
    [InlineData(0, 0, 1, 60)]
    [InlineData(0, 1, -1, 60)]
    [InlineData(1, 0, 1, 300)]
    [InlineData(1, 1, -1, 300)]
    public void Parse_ArcFlags_PickOneOfTheFourArcs(int large, int sweep, int side, double degrees)
    {
        // Radius 10 between points 10 apart: the small arcs turn 60°, the large ones 300°. Sweep 1 turns towards
        // +angle, clockwise on screen (y down): from the left point to the right one that bows the arc up (y below 50).
        var drawing = Parse($"<path d=\"M0 50 A10 10 0 {large} {sweep} 10 50\"/>");

        var points = Points(drawing.Paths[0]);
        Assert.Equal(10 * degrees * Math.PI / 180, Length(points), 4);
        var farthest = points.MaxBy(p => Math.Abs(p.Y - 50));
        Assert.Equal(side, Math.Sign(farthest.Y - 50));
        Assert.Equal(new DrawingPoint(10, 50), points[^1]);
    }

    [Fact]
    public void Parse_ArcRadiiTooSmall_ScaleUpToAHalfCircle()
    {
        var drawing = Parse("<path d=\"M0 50 A1 1 0 0 1 30 50\"/>");

        Assert.Equal(15 * Math.PI, Length(Points(drawing.Paths[0])), 4);
    }

    [Fact]
    public void Parse_RotatedEllipticalArc_EndsOnTheMajorAxis()
    {
        // Half of a 20 x 10 ellipse tilted 30°, from one end of its major axis to the other: half its perimeter.
        double c = Math.Cos(Math.PI / 6), s = Math.Sin(Math.PI / 6);
        var drawing = Parse(FormattableString.Invariant($"<path d=\"M10 10 a20 10 30 0 1 {40 * c} {40 * s}\"/>"));

        const int n = 100_000;
        var half = Enumerable.Range(0, n).Sum(i =>
        {
            var t = (i + 0.5) * Math.PI / n;
            return Math.Sqrt(Math.Pow(20 * Math.Sin(t), 2) + Math.Pow(10 * Math.Cos(t), 2)) * Math.PI / n;
        });
        var points = Points(drawing.Paths[0]);
        Assert.InRange(Length(points), half * (1 - 1e-7), half);
        Assert.Equal(10 + (40 * c), points[^1].X, 9);
    }

    [Fact]
    public void Parse_Transforms_ApplyRightToLeftAndNestFromTheOutside()
    {
        // The line (1,0)-(2,0) rotated 90° (to (0,1)-(0,2)), then moved by (10,0); the group then scales by 2.
        var drawing = Parse("<g transform=\"scale(2)\"><line x1=\"1\" y1=\"0\" x2=\"2\" y2=\"0\" transform=\"translate(10,0) rotate(90)\"/></g>");

        Assert.Equal(new DrawingPoint(20, 2), drawing.Paths[0].Start);
        Assert.Equal(new DrawingPoint(20, 4), drawing.Paths[0].End);
    }

    [Theory]
    [InlineData("matrix(1 0 0 1 5 6)", 6, 6)]
    [InlineData("translate(5)", 6, 0)]
    [InlineData("rotate(180 1 0)", 1, 0)]
    [InlineData("skewX(45)", 2, 1)]
    [InlineData("skewY(45)", 1, 2)]
    [InlineData("scale(2, 3)", 2, 3)]
    public void Parse_EachTransformFunction_MovesThePointAsDefined(string transform, double x, double y)
    {
        var drawing = Parse($"<line x1=\"1\" y1=\"{(transform.StartsWith("skewX", StringComparison.Ordinal) || transform.StartsWith("skewY", StringComparison.Ordinal) || transform.StartsWith("scale", StringComparison.Ordinal) ? 1 : 0)}\" x2=\"50\" y2=\"50\" transform=\"{transform}\"/>");

        Assert.Equal(x, drawing.Paths[0].Start.X, 12);
        Assert.Equal(y, drawing.Paths[0].Start.Y, 12);
    }

    [Fact]
    public void Parse_SkewedCircle_IsTheSkewedEllipseExactly()
    {
        var drawing = Parse("<circle cx=\"0\" cy=\"0\" r=\"10\" transform=\"skewX(30)\"/>");

        var tan = Math.Tan(Math.PI / 6);
        Assert.All(Points(drawing.Paths[0]), p =>
        {
            // Undo the skew: x = x' - tan(30°) y'; the point is then on the circle.
            var x = p.X - (tan * p.Y);
            Assert.Equal(10, Math.Sqrt((x * x) + (p.Y * p.Y)), 9);
        });
    }

    [Fact]
    public void Parse_Shapes_HaveTheirExactLengths()
    {
        var drawing = Parse(
            "<rect x=\"10\" y=\"10\" width=\"40\" height=\"20\" rx=\"5\"/>" +
            "<rect x=\"0\" y=\"0\" width=\"3\" height=\"4\"/>" +
            "<circle cx=\"50\" cy=\"50\" r=\"8\"/>" +
            "<line x1=\"0\" y1=\"0\" x2=\"3\" y2=\"4\"/>" +
            "<polyline points=\"0,0 3,4 6,0\"/>" +
            "<polygon points=\"0,0 3,4 6,0\"/>");

        double[] exact = [(2 * 30) + (2 * 10) + (2 * Math.PI * 5), 14, 2 * Math.PI * 8, 5, 10, 16];
        Assert.Equal(exact.Length, drawing.Paths.Count);
        for (var i = 0; i < exact.Length; i++)
        {
            Assert.InRange(Length(drawing.Paths[i].Flatten(1e-7)), exact[i] * (1 - 1e-7), exact[i] * (1 + 1e-12));
        }

        Assert.Equal([true, true, true, false, false, true], drawing.Paths.Select(p => p.Closed));
    }

    [Fact]
    public void Parse_TextImageAndHidden_AreNamedInWarningsNotDrawn()
    {
        var drawing = Parse(
            "<text id=\"title\" x=\"0\" y=\"10\">Hi</text><text x=\"0\" y=\"20\">there</text>" +
            "<image id=\"photo\" href=\"a.png\" width=\"5\" height=\"5\"/>" +
            "<g style=\"fill:red; display : none\"><circle cx=\"1\" cy=\"1\" r=\"1\"/></g>" +
            "<circle id=\"shown\" cx=\"5\" cy=\"5\" r=\"1\"/>");

        Assert.Single(drawing.Paths);
        Assert.Contains(drawing.Warnings, w => w.StartsWith("2 <text> (#title, line ", StringComparison.Ordinal) && w.Contains("convert it to paths", StringComparison.Ordinal));
        Assert.Contains(drawing.Warnings, w => w.StartsWith("1 <image> (#photo)", StringComparison.Ordinal));
        Assert.Contains(drawing.Warnings, w => w.StartsWith("1 <g>", StringComparison.Ordinal) && w.Contains("hidden", StringComparison.Ordinal));
    }

    [Fact]
    public void Parse_Use_DrawsTheReferencedShapeMoved()
    {
        var drawing = Parse("<defs><circle id=\"dot\" cx=\"0\" cy=\"0\" r=\"1\"/></defs><use href=\"#dot\" x=\"10\" y=\"20\"/>");

        var path = Assert.Single(drawing.Paths);
        Assert.Equal(new DrawingPoint(11, 20), path.Start);
    }

    [Theory]
    [InlineData("<path id=\"p1\" d=\"M0 0 L10\"/>", "<path> id \"p1\" (line 2): path data at character")]
    [InlineData("<path d=\"M0 0 X10 10\"/>", "'X' is not a path command")]
    [InlineData("<path d=\"L10 10\"/>", "must begin with M")]
    [InlineData("<path d=\"M0 0 A5 5 0 2 0 10 10\"/>", "arc flag")]
    [InlineData("<g transform=\"spin(3)\"><line x2=\"1\"/></g>", "transform \"spin(3)\"")]
    [InlineData("<polygon id=\"tri\" points=\"0,0 1\"/>", "<polygon> id \"tri\"")]
    [InlineData("<circle r=\"5em\"/>", "r=\"5em\"")]
    [InlineData("<use href=\"#nowhere\"/>", "names no element")]
    public void Parse_BadElement_ThrowsNamingFileElementAndProblem(string body, string expected)
    {
        var ex = Assert.Throws<DrawingException>(() => Parse(body));

        Assert.StartsWith("t.svg: <", ex.Message, StringComparison.Ordinal);
        Assert.Contains(expected, ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Parse_NotXmlOrNotSvg_ThrowsNamingTheFile()
    {
        Assert.StartsWith("x.svg: not well-formed XML", Assert.Throws<DrawingException>(() => SvgReader.Parse("<svg", "x.svg")).Message, StringComparison.Ordinal);
        Assert.Contains("not <svg>", Assert.Throws<DrawingException>(() => SvgReader.Parse("<html/>", "x.svg")).Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Plan_TextNotConvertedToPaths_ThrowsNamingTheTextElement()
    {
        var ex = Assert.Throws<DrawingException>(() => VectorPlanner.Plan(File("text.svg"), VectorOptions.Default, Core.Geometry.MachineProfile.Default));

        Assert.Contains("nothing to burn", ex.Message, StringComparison.Ordinal);
        Assert.Contains("<text> (#mark)", ex.Message, StringComparison.Ordinal);
        Assert.Contains("Object to Path", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Read_TextConvertedToPathsByInkscape_ReadsEveryGlyphOutline()
    {
        var drawing = SvgReader.Read(File("text-as-paths.svg"));

        // L, E, -, 1 and the 4 with its hole; Inkscape's own metadata and defs give no warning.
        Assert.Equal(6, drawing.Paths.Count);
        Assert.All(drawing.Paths, p => Assert.True(p.Closed));
        Assert.Empty(drawing.Warnings);
        Assert.True(drawing.UnitsStated);
    }

    [Fact]
    public void Read_EveryCommandDrawing_WarnsAboutTextAndHiddenGroup()
    {
        var drawing = SvgReader.Read(File("every-command.svg"));

        var expected = Expected("every-command.svg");
        Assert.Equal(expected.GetProperty("paths").GetInt32(), drawing.Paths.Count);
        Assert.Contains(drawing.Warnings, w => w.Contains("<text> (#label)", StringComparison.Ordinal));
        Assert.Contains(drawing.Warnings, w => w.Contains("<g> (#hidden)", StringComparison.Ordinal));
    }
}
