using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Vectors;
using static LaserEngrave.Core.Tests.Vectors.TestDrawings;

namespace LaserEngrave.Core.Tests.Vectors;

public class VectorPlannerTests
{
    private static readonly MachineProfile Profile = MachineProfile.Default;

    /// <summary>A profile with room for the larger test drawings.</summary>
    private static readonly MachineProfile Wide = MachineProfile.Default with
    {
        X = MachineProfile.Default.X with { TravelMm = 200 },
        Y = MachineProfile.Default.Y with { TravelMm = 200 },
    };

    [Theory]
    [InlineData("hexagons.dxf")]
    [InlineData("scattered.dxf")]
    [InlineData("curves.dxf")]
    [InlineData("curves-r12.dxf")]
    [InlineData("blocks.dxf")]
    [InlineData("every-command.svg")]
    public void Plan_TestDrawing_BurnLengthWithinATenThousandthOfExact(string name)
    {
        var expected = Expected(name);
        var exact = expected.GetProperty("lengthMm").GetDouble();

        var plan = VectorPlanner.Plan(File(name), new VectorOptions { Origin = new OriginMm(5, 5) }, Wide);

        // 0.01 %, plus for arcs of radius r the s / (3 r) their chords must lose at tolerance s (the sum of length / r).
        var allowed = (1e-4 * exact) + (plan.ToleranceUm / 1000 / 3 * expected.GetProperty("lengthOverRadius").GetDouble());
        Assert.InRange(BurnLengthMm(plan), exact - allowed, exact + allowed);
        Assert.Equal(BurnLengthMm(plan), plan.BurnLengthMm, 9);
    }

    [Theory]
    [InlineData(0.2, 1.0)]
    [InlineData(0.2, 0.1)]
    [InlineData(1.0, 1.0)]
    public void Plan_SmallCircle_ShortOfExactByAtMostToleranceOverThreeRadii(double radiusMm, double toleranceUm)
    {
        var drawing = DxfReader.Parse(Dxf(Entity("CIRCLE", (10, 5), (20, 5), (40, radiusMm))), "c.dxf");

        var plan = VectorPlanner.Plan(drawing, new VectorOptions { ToleranceUm = toleranceUm, Origin = new OriginMm(10, 10) }, Profile);

        var exact = 2 * Math.PI * radiusMm;
        var bound = toleranceUm / 1000 / (3 * radiusMm);

        // Rounding each vertex to a 0.1 µm microstep adds a little noise: allow 2 % of the bound on top of it.
        var shortfall = (exact - BurnLengthMm(plan)) / exact;
        Assert.InRange(shortfall, 0, bound * 1.02);
        Assert.True(shortfall > bound * 0.5, $"shortfall {shortfall} is far below {bound}: the tolerance is not used");
    }

    [Fact]
    public void Plan_PolylineVertices_AreTheirExactPositionsRoundedOnce()
    {
        (double X, double Y)[] vertices = [(1.2345678, 2.3456789), (13.579, 2.4681357), (7.7777777, 11.1111111), (0.3333333, 9.8765432)];
        var drawing = DxfReader.Parse(Dxf(LwPolyline(true, [.. vertices.Select(v => (v.X, v.Y, 0.0))])), "v.dxf");
        double minX = vertices.Min(v => v.X), maxY = vertices.Max(v => v.Y);

        var own = VectorPlanner.Plan(drawing, new VectorOptions { Origin = new OriginMm(10, 7.5) }, Profile);
        var scaled = VectorPlanner.Plan(drawing, new VectorOptions { Origin = new OriginMm(10, 7.5), WidthMm = 5 }, Profile);

        // DXF y grows up: the stage's y runs down from the top of the drawing.
        var scale = 5 / (vertices.Max(v => v.X) - minX);
        var outline = Assert.Single(own.Paths);
        var scaledOutline = Assert.Single(scaled.Paths);
        foreach (var (x, y) in vertices)
        {
            Assert.Contains(new StagePoint(Microsteps(10 + (x - minX)), Microsteps(7.5 + (maxY - y))), outline.Points);
            Assert.Contains(new StagePoint(Microsteps(10 + ((x - minX) * scale)), Microsteps(7.5 + ((maxY - y) * scale))), scaledOutline.Points);
        }

        Assert.Equal(5, scaled.WidthMm, 12);
    }

    [Fact]
    public void Plan_HexagonsDrawing_EveryVertexAtItsExactPositionRoundedOnce()
    {
        var expected = Expected("hexagons.dxf");
        var bounds = expected.GetProperty("bounds").EnumerateArray().Select(b => b.GetDouble()).ToArray();

        var plan = VectorPlanner.Plan(File("hexagons.dxf"), new VectorOptions { Origin = new OriginMm(3, 4) }, Profile);

        var burned = plan.Paths.SelectMany(p => p.Points).ToHashSet();
        foreach (var v in expected.GetProperty("vertices").EnumerateArray())
        {
            double x = v[0].GetDouble(), y = v[1].GetDouble();
            Assert.Contains(new StagePoint(Microsteps(3 + (x - bounds[0])), Microsteps(4 + (bounds[3] - y))), burned);
        }
    }

    [Fact]
    public void Plan_PolylineOfManyShortSegments_ClosesOnItsFirstMicrostep()
    {
        // Seed 001's lesson: 3000 steps of 1/3 µm would drift if each were rounded as a relative move.
        var points = Enumerable.Range(0, 3000).Select(i => (i / 3000.0, 0.0, 0.0))
            .Concat(Enumerable.Range(0, 3000).Select(i => (1.0, i / 3000.0, 0.0)))
            .Concat(Enumerable.Range(0, 3000).Select(i => (1 - (i / 3000.0), 1.0, 0.0)))
            .Concat(Enumerable.Range(0, 3000).Select(i => (0.0, 1 - (i / 3000.0), 0.0)))
            .ToArray();
        var drawing = DxfReader.Parse(Dxf(LwPolyline(true, points)), "many.dxf");

        var plan = VectorPlanner.Plan(drawing, new VectorOptions { Origin = new OriginMm(1, 1) }, Profile);

        var path = Assert.Single(plan.Paths);
        Assert.Equal(path.Points[0], path.Points[^1]);
        Assert.Contains(new StagePoint(Microsteps(2), Microsteps(2)), path.Points);
        // Along each side the rounded steps add up to the difference of its rounded corners.
        var side = Microsteps(2) - Microsteps(1);
        Assert.Equal(4 * side * MicrostepUm / 1000, plan.BurnLengthMm, 9);
    }

    [Fact]
    public void Plan_SixLinesOfAHexagon_JoinIntoOneClosedContour()
    {
        var corners = Enumerable.Range(0, 6).Select(k => (X: 5 * Math.Cos(k * Math.PI / 3), Y: 5 * Math.Sin(k * Math.PI / 3))).ToArray();

        // Drawn out of order and some backwards, as CAD exports do.
        var lines = new[] { 3, 0, 5, 1, 4, 2 }.Select(k => k % 2 == 0
            ? Entity("LINE", (10, corners[k].X), (20, corners[k].Y), (11, corners[(k + 1) % 6].X), (21, corners[(k + 1) % 6].Y))
            : Entity("LINE", (10, corners[(k + 1) % 6].X), (20, corners[(k + 1) % 6].Y), (11, corners[k].X), (21, corners[k].Y)));
        var drawing = DxfReader.Parse(Dxf(string.Concat(lines)), "hex.dxf");

        var plan = VectorPlanner.Plan(drawing, new VectorOptions { Origin = new OriginMm(10, 10) }, Profile);

        var path = Assert.Single(plan.Paths);
        Assert.True(path.Closed);
        Assert.Equal(7, path.Points.Count);
        double minX = corners.Min(c => c.X), maxY = corners.Max(c => c.Y);
        var rounded = corners.Select(c => new StagePoint(Microsteps(10 + c.X - minX), Microsteps(10 + maxY - c.Y))).ToArray();
        var perimeter = Enumerable.Range(0, 6).Sum(k => Distance(rounded[k], rounded[(k + 1) % 6])) * MicrostepUm / 1000;
        Assert.Equal(perimeter, plan.BurnLengthMm, 9);
        Assert.Equal(rounded.ToHashSet(), path.Points.ToHashSet());
    }

    [Fact]
    public void Plan_OutsideTheTravel_WarnsAndSaysItDoesNotFit()
    {
        var drawing = DxfReader.Parse(Dxf(Entity("LINE", (10, 0), (20, 0), (11, 10), (21, 0))), "l.dxf");

        var plan = VectorPlanner.Plan(drawing, new VectorOptions { Origin = new OriginMm(55, 0) }, Profile);

        Assert.False(plan.FitsTravel);
        Assert.Contains(plan.Warnings, w => w.Contains("outside the stage's travel", StringComparison.Ordinal));
    }

    [Theory]
    [InlineData(0.0)]
    [InlineData(-1.0)]
    [InlineData(double.NaN)]
    public void Plan_BadWidth_ThrowsNamingIt(double width)
    {
        var drawing = DxfReader.Parse(Dxf(Entity("LINE", (10, 0), (20, 0), (11, 10), (21, 0))), "l.dxf");

        Assert.Contains("width", Assert.Throws<GeometryException>(() => VectorPlanner.Plan(drawing, new VectorOptions { WidthMm = width }, Profile)).Message, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData(0, false, false, new double[] { 10, 10, 14, 10, 14, 11 })]
    [InlineData(1, false, false, new double[] { 11, 10, 11, 14, 10, 14 })]
    [InlineData(2, false, false, new double[] { 14, 11, 10, 11, 10, 10 })]
    [InlineData(1, true, false, new double[] { 11, 14, 11, 10, 10, 10 })]
    [InlineData(0, false, true, new double[] { 10, 11, 14, 11, 14, 10 })]
    public void Plan_TurnedOrMirrored_TheDrawingAsItLiesOnTheStageWithItsCornerOnTheOrigin(int quarterTurns, bool mirrorX, bool mirrorY, double[] expectedMm)
    {
        // An L: 4 mm right, then 1 mm down (SVG's y runs down, as the stage's).
        var drawing = SvgReader.Parse(Svg("<path d=\"M 0 0 L 4 0 L 4 1\" fill=\"none\" stroke=\"black\"/>"), "l.svg");

        var plan = VectorPlanner.Plan(drawing, new VectorOptions { Origin = new OriginMm(10, 10), QuarterTurns = quarterTurns, MirrorX = mirrorX, MirrorY = mirrorY }, Profile);

        var points = Assert.Single(plan.Paths).Points.Select(p => (Math.Round(p.X * MicrostepUm / 1000, 4), Math.Round(p.Y * MicrostepUm / 1000, 4))).ToList();
        var expected = Enumerable.Range(0, 3).Select(i => (expectedMm[2 * i], expectedMm[(2 * i) + 1])).ToList();

        // The path may be burned from either end.
        Assert.True(points.SequenceEqual(expected) || points.SequenceEqual(Enumerable.Reverse(expected)), $"burned {string.Join(" ", points)}");
        Assert.Equal(quarterTurns % 2 == 0 ? (4, 1) : (1, 4), (Math.Round(plan.WidthMm, 6), Math.Round(plan.HeightMm, 6)));
    }

    [Fact]
    public void Plan_TurnedAndSizedByWidth_TheWidthIsTheTurnedDrawings()
    {
        var drawing = SvgReader.Parse(Svg("<path d=\"M 0 0 L 4 0 L 4 1\" fill=\"none\" stroke=\"black\"/>"), "l.svg");

        var plan = VectorPlanner.Plan(drawing, new VectorOptions { Origin = new OriginMm(10, 10), QuarterTurns = 3, WidthMm = 2 }, Profile);

        Assert.Equal((2, 8), (Math.Round(plan.WidthMm, 6), Math.Round(plan.HeightMm, 6)));
    }

    [Fact]
    public void Validate_FiveQuarterTurns_RefusedWithOneLine()
    {
        var ex = Assert.Throws<GeometryException>(() => new VectorOptions { QuarterTurns = 5 }.Validate());

        Assert.Equal("quarter turns 5 must be 0, 1, 2 or 3 (0°, 90°, 180°, 270° clockwise)", ex.Message);
    }
}
