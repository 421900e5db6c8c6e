using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Preview;
using LaserEngrave.Core.Vectors;
using static LaserEngrave.Core.Tests.Vectors.TestDrawings;

namespace LaserEngrave.Core.Tests.Vectors;

public class ScanlineFillTests
{
    private static List<DrawingPoint> Square(double x, double y, double size) =>
        [new(x, y), new(x + size, y), new(x + size, y + size), new(x, y + size), new(x, y)];

    [Fact]
    public void Rows_SquareWithSquareHole_EvenOddLeavesTheHoleUnburned()
    {
        var rows = ScanlineFill.Rows([Square(0, 0, 1000), Square(300, 300, 400)], 10);

        Assert.Equal(100, rows.Count);
        foreach (var row in rows)
        {
            var expected = row.Y is > 300 and < 700 ? new[] { (0L, 300L), (700L, 1000L) } : new[] { (0L, 1000L) };
            Assert.Equal(expected, row.Segments);
        }

        Assert.Equal(((1000 * 1000) - (400 * 400)) / 10, rows.Sum(r => r.Segments.Sum(s => s.X1 - s.X0)));
    }

    [Fact]
    public void Rows_FractionalPitch_RowsAtTopPlusHalfPitchRoundedOnce()
    {
        const double pitch = 7.3;
        var rows = ScanlineFill.Rows([Square(0.4, 100.2, 500)], pitch);

        Assert.Equal(Enumerable.Range(0, rows.Count).Select(k => (long)Math.Round(100.2 + ((k + 0.5) * pitch), MidpointRounding.AwayFromZero)), rows.Select(r => r.Y));
        Assert.Equal((int)Math.Floor((500 / pitch) + 0.5), rows.Count);
    }

    [Fact]
    public void Rows_Triangle_SegmentsFollowTheSlantedEdges()
    {
        // Apex at the top: the row at height y spans x = ±(y / 2) about 500.
        var rows = ScanlineFill.Rows([[new(500, 0), new(1000, 1000), new(0, 1000), new(500, 0)]], 100);

        foreach (var row in rows)
        {
            var (x0, x1) = Assert.Single(row.Segments);
            Assert.Equal((long)Math.Round(500 - (row.Y / 2.0), MidpointRounding.AwayFromZero), x0);
            Assert.Equal((long)Math.Round(500 + (row.Y / 2.0), MidpointRounding.AwayFromZero), x1);
        }
    }

    [Fact]
    public void Plan_FillBoth_FillsFirstThenOutlinesInSerpentineRows()
    {
        var drawing = SvgReader.Parse(Svg("<rect x=\"10\" y=\"10\" width=\"2\" height=\"1\"/><rect x=\"10.5\" y=\"10.25\" width=\"1\" height=\"0.5\"/>"), "f.svg");

        var plan = VectorPlanner.Plan(drawing, new VectorOptions { Fill = VectorFillMode.Both, FillPitchUm = 50, Origin = new OriginMm(1, 1) }, MachineProfile.Default);

        Assert.Equal(20, plan.FillRows.Count);
        var kinds = plan.Paths.Select(p => p.Kind).ToList();
        Assert.Equal(kinds.Count(k => k == VectorPathKind.Fill), kinds.TakeWhile(k => k == VectorPathKind.Fill).Count());
        Assert.Equal(2, kinds.Count(k => k == VectorPathKind.Outline));

        // 2 x 1 mm less the 1 x 0.5 mm hole, at 50 µm between rows: 1.5 mm² / 0.05 mm = 30 mm of fill.
        var fill = plan.Paths.Where(p => p.Kind == VectorPathKind.Fill).Sum(p => p.LengthMicrosteps) * MicrostepUm / 1000;
        Assert.Equal(30, fill, 2);
        var firstRow = plan.Paths.Where(p => p.Kind == VectorPathKind.Fill).First();
        var lastOfSecondRow = plan.Paths.First(p => p.Kind == VectorPathKind.Fill && p.Start.Y == plan.FillRows[1].Y);
        Assert.True(firstRow.End.X > firstRow.Start.X);
        Assert.True(lastOfSecondRow.End.X < lastOfSecondRow.Start.X);
    }

    [Fact]
    public void Plan_FillOfSeparateShapes_FillsOneAreaAfterTheOtherOnSharedScanLines()
    {
        // Two 1 mm squares 5 mm apart, the right one 0.013 mm lower: one fill after the other, not rows across both.
        var drawing = SvgReader.Parse(Svg("<rect x=\"10\" y=\"10\" width=\"1\" height=\"1\"/><rect x=\"16\" y=\"10.013\" width=\"1\" height=\"1\"/>"), "two.svg");

        var plan = VectorPlanner.Plan(drawing, new VectorOptions { Fill = VectorFillMode.Fill, FillPitchUm = 100, Origin = new OriginMm(1, 1) }, MachineProfile.Default);

        var fills = plan.Paths.Where(p => p.Kind == VectorPathKind.Fill).ToList();
        var left = fills.TakeWhile(p => p.Start.X < Microsteps(4)).Count();
        Assert.Equal(10, left);
        Assert.All(fills.Skip(left), p => Assert.True(p.Start.X > Microsteps(6)));

        // Both on the scan lines of the drawing's top: y = 1 mm + (k + 1/2) 0.1 mm, rounded once.
        var lines = Enumerable.Range(0, 11).Select(k => Microsteps(1 + ((k + 0.5) * 0.1))).ToHashSet();
        Assert.All(fills, p => Assert.Contains(p.Start.Y, lines));
        Assert.Equal(20, fills.Count);
    }

    [Fact]
    public void Regions_OverlappingBoxes_StayTogether()
    {
        var regions = ScanlineFill.Regions([Square(0, 0, 10), Square(100, 0, 10), Square(5, 5, 10), Square(14, 14, 3)]);

        Assert.Equal([3, 1], regions.Select(r => r.Count).OrderDescending());
    }

    [Fact]
    public void Draw_Plan_BurnsBlackTravelsInTravelColoursStartGreen()
    {
        var plan = VectorPlanner.Plan(File("hexagons.dxf"), new VectorOptions { Origin = new OriginMm(2, 2) }, MachineProfile.Default);

        var canvas = VectorPreview.Draw(plan, 400);

        Assert.Equal(400, Math.Max(canvas.Width, canvas.Height));
        var colours = new Dictionary<Rgba, int>();
        for (var y = 0; y < canvas.Height; y++)
        {
            for (var x = 0; x < canvas.Width; x++)
            {
                colours[canvas[x, y]] = colours.GetValueOrDefault(canvas[x, y]) + 1;
            }
        }

        Assert.True(colours.GetValueOrDefault(PlanPreview.BurnColour) > 1000);
        Assert.True(colours.GetValueOrDefault(PlanPreview.StartMarkerColour) > 10);
        Assert.Contains(colours.Keys, c => c.B > 150 && c.G < 200 && c != PlanPreview.Background);
    }
}
