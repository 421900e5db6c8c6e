using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Preview;
using LaserEngrave.Core.Tests.Planning;

namespace LaserEngrave.Core.Tests.Preview;

public class PlanPreviewTests
{
    // 10 x 4 pixels at 1000 microsteps, origin (2000, 0): the job spans x 2000..12000, y 0..4000.
    private static RasterPlan Plan(double overscanMm = 0, PlanStrategy strategy = PlanStrategy.Optimized)
    {
        var mask = TestMasks.FromRows("##....##..", "..........", "...####...", "#........#");
        return new RasterPlan(mask, TestMasks.Geometry(mask, ox: 2000), new PlanOptions { OverscanMm = overscanMm, Strategy = strategy });
    }

    [Fact]
    public void Draw_Plan_BurnsAreBurnColourOnTheirRowLines()
    {
        var plan = Plan();
        var canvas = PlanPreview.Draw(plan, 512);
        var map = Map(plan, canvas);
        foreach (var burn in plan.Moves().Where(m => m.Kind == MoveKind.Burn))
        {
            Assert.Equal(PlanPreview.BurnColour, canvas[map.X((burn.X0 + burn.X1) / 2), map.Y(burn.Y0)]);
        }
    }

    [Fact]
    public void Draw_Plan_TravelsShadeFromStartColourToEndColour()
    {
        var plan = Plan();
        var canvas = PlanPreview.Draw(plan, 512);
        var map = Map(plan, canvas);
        var travels = plan.Moves().Where(m => m.Kind == MoveKind.Travel && m.Y0 == m.Y1).ToList();
        var first = canvas[map.X((travels[0].X0 + travels[0].X1) / 2), map.Y(travels[0].Y0)];
        var last = canvas[map.X((travels[^1].X0 + travels[^1].X1) / 2), map.Y(travels[^1].Y0)];

        Assert.True(Distance(first, PlanPreview.TravelStartColour) < Distance(first, PlanPreview.TravelEndColour), $"first travel {first}");
        Assert.True(Distance(last, PlanPreview.TravelEndColour) < Distance(last, PlanPreview.TravelStartColour), $"last travel {last}");
    }

    [Fact]
    public void Draw_Overscan_DrawsItInItsOwnColour()
    {
        var plan = Plan(overscanMm: 500 * TestMasks.Microstep / 1000);
        var canvas = PlanPreview.Draw(plan, 512);
        var map = Map(plan, canvas);
        var runUp = plan.Moves().First(m => m.Kind == MoveKind.Overscan && m.LengthX == 500);
        Assert.Equal(PlanPreview.OverscanColour, canvas[map.X((runUp.X0 + runUp.X1) / 2), map.Y(runUp.Y0)]);
    }

    [Fact]
    public void Draw_Plan_MarksTheStartAndOutlinesTheJob()
    {
        var plan = Plan();
        var canvas = PlanPreview.Draw(plan, 512);
        var map = Map(plan, canvas);
        var start = plan.Moves().First();
        Assert.Equal(PlanPreview.StartMarkerColour, canvas[map.X(start.X0), map.Y(start.Y0)]);
        Assert.Equal(PlanPreview.JobOutline, canvas[map.X(7000), map.Y(0)]);
        Assert.Equal(PlanPreview.JobFill, canvas[map.X(7000), map.Y(1500)]);
        Assert.Equal(PlanPreview.Background, canvas[0, canvas.Height - 1]);
    }

    [Fact]
    public void Draw_Plan_FitsTheMaximumSide()
    {
        var canvas = PlanPreview.Draw(Plan(), 300);
        Assert.Equal(300, canvas.Width);
        Assert.InRange(canvas.Height, 100, 140);
    }

    [Fact]
    public void Render_Plan_WritesTheDrawnPixels()
    {
        var plan = Plan(strategy: PlanStrategy.Paper);
        using var png = new MemoryStream();
        PlanPreview.Render(plan, png, 200);
        var (width, height, channels, pixels) = PngFile.Read(png.ToArray());
        var canvas = PlanPreview.Draw(plan, 200);
        Assert.Equal((canvas.Width, canvas.Height, 4), (width, height, channels));
        Assert.Equal(canvas.Pixels.ToArray(), pixels);
    }

    [Fact]
    public void Draw_RowsDenserThanThePreview_HatchesTravelsSoTheWhiteShows()
    {
        // 600 rows of "burn, long white gap, burn" into about 100 preview pixels: 6 image rows per preview line.
        var mask = new BitMask(200, 600);
        for (var y = 0; y < mask.Height; y++)
        {
            mask[0, y] = true;
            mask[199, y] = true;
        }

        var canvas = PlanPreview.Draw(new RasterPlan(mask, TestMasks.Geometry(mask)), 100);
        var middle = canvas.Width / 2;
        for (var y = 10; y < canvas.Height - 10; y++)
        {
            var colour = canvas[middle, y];
            if (y % 3 == 0)
            {
                Assert.NotEqual(PlanPreview.JobFill, colour);
            }
            else
            {
                Assert.Equal(PlanPreview.JobFill, colour);
            }
        }
    }

    [Fact]
    public void Draw_BlankPlan_IsJustTheOutline()
    {
        var mask = TestMasks.FromRows("....", "....");
        var canvas = PlanPreview.Draw(new RasterPlan(mask, TestMasks.Geometry(mask)), 100);
        var colours = new HashSet<Rgba>();
        for (var y = 0; y < canvas.Height; y++)
        {
            for (var x = 0; x < canvas.Width; x++)
            {
                colours.Add(canvas[x, y]);
            }
        }

        Assert.Equal([PlanPreview.Background, PlanPreview.JobFill, PlanPreview.JobOutline], colours.OrderByDescending(c => c.R));
    }

    [Theory]
    [InlineData(5)]
    [InlineData(PlanPreview.MaxSidePx + 1)]
    public void Draw_UnusableSize_Throws(int maxSide)
    {
        Assert.Throws<ArgumentOutOfRangeException>(() => PlanPreview.Draw(Plan(), maxSide));
    }

    private static int Distance(Rgba a, Rgba b) => Math.Abs(a.R - b.R) + Math.Abs(a.G - b.G) + Math.Abs(a.B - b.B);

    /// <summary>Stage microsteps to canvas pixels, recomputed from the canvas size: the job spans x 2000..12000 into the width minus the margins.</summary>
    private static (Func<long, int> X, Func<long, int> Y) Map(RasterPlan plan, RgbaCanvas canvas)
    {
        const int Margin = 6;
        var left = plan.Geometry.EdgeX(0) - plan.OverscanMicrosteps;
        var right = plan.Geometry.EdgeX(plan.Geometry.WidthPx) + plan.OverscanMicrosteps;
        var scale = (canvas.Width - (2 * Margin) - 1) / (double)(right - left);
        return (x => Margin + (int)Math.Round((x - left) * scale), y => Margin + (int)Math.Round(y * scale));
    }
}
