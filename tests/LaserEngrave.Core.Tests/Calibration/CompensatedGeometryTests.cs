using LaserEngrave.Core.Calibration;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Calibration;

public class CompensatedGeometryTests
{
    private static readonly AxisCalibration Machine = new() { SquarenessDegrees = 0.5, ScaleXPpm = 500, ScaleYPpm = -500 };

    [Fact]
    public void RunEdgeX_CalibratedMachine_ShiftsEachRowByItsYTimesTanG()
    {
        // 1000 microsteps per pixel, origin (5000, 7000): row 10's centre is 10500 microsteps below the origin.
        var geometry = new JobGeometry(100, 100, 1000, 5000, 7000, 0.1, 1_000_000, 1_000_000, new StageCompensation(Machine));
        var g = 0.5 * Math.PI / 180;

        var x = geometry.RunEdgeX(20, 10);
        var y = geometry.RowY(10);

        Assert.Equal((long)Math.Round(5000 + ((20_000 + (10_500 * Math.Tan(g))) / 1.0005)), x);
        Assert.Equal((long)Math.Round(7000 + (10_500 / (0.9995 * Math.Cos(g)))), y);
    }

    [Fact]
    public void EdgeX_NoCalibration_SameAsUncompensatedFormula()
    {
        var geometry = new JobGeometry(100, 100, 403.2, 100_000.5, 7000, 0.1, 1_000_000, 1_000_000);

        Assert.Equal(JobGeometry.Round(Math.FusedMultiplyAdd(37, 403.2, 100_000.5)), geometry.RunEdgeX(37, 55));
        Assert.Equal(geometry.EdgeX(37), geometry.RunEdgeX(37, 99));
    }

    [Fact]
    public void Plan_CalibratedMachine_BurnsStaySingleAxisAndLandOnTheCompensatedEdges()
    {
        var mask = new BitMask(40, 30);
        for (var y = 0; y < 30; y++)
        {
            mask[3, y] = mask[4, y] = mask[30, y] = true;
        }

        var geometry = new JobGeometry(40, 30, 400, 50_000, 60_000, 0.1, 1_000_000, 1_000_000, new StageCompensation(Machine));
        var plan = new RasterPlan(mask, geometry, new PlanOptions { Strategy = PlanStrategy.Optimized, OverscanMm = 0.01 });

        var burns = plan.Moves().Where(m => m.Kind == MoveKind.Burn).ToList();

        Assert.Equal(60, burns.Count);
        Assert.All(burns, b => Assert.Equal(b.Y0, b.Y1));
        var g = 0.5 * Math.PI / 180;
        foreach (var burn in burns)
        {
            // The run of columns 3..5 of this row, from absolute true coordinates, rounded once.
            var rowY = (burn.Row + 0.5) * 400;
            long Edge(int column) => (long)Math.Round(50_000 + (((column * 400) + (rowY * Math.Tan(g))) / 1.0005), MidpointRounding.AwayFromZero);
            var (left, right) = (Math.Min(burn.X0, burn.X1), Math.Max(burn.X0, burn.X1));
            Assert.True((left, right) == (Edge(3), Edge(5)) || (left, right) == (Edge(30), Edge(31)), $"row {burn.Row}: {left}..{right}");
            Assert.Equal((long)Math.Round(60_000 + (rowY / (0.9995 * Math.Cos(g))), MidpointRounding.AwayFromZero), burn.Y0);
        }
    }

    [Fact]
    public void Resolve_CalibratedProfile_AchievedSizeIsTheTrueSize()
    {
        var profile = MachineProfile.Default with { Calibration = Machine };

        var report = GeometryResolver.Resolve(SizeSpec.Width(10), 1000, 500, new OriginMm(5, 5), profile);

        // The stage moves 10 mm / 1.0005 so the sample moves 10 mm; the report speaks of the sample.
        Assert.Equal(10, report.AchievedWidthMm, 3);
        Assert.Equal(5, report.AchievedHeightMm, 3);
        Assert.False(report.Geometry.Compensation.IsIdentity);
    }

    [Fact]
    public void Resolve_ShearPastTheStageZero_DoesNotFitTheTravel()
    {
        // At -0.5° each row shifts left by its depth x tan 0.5°: a 10 mm tall job at x = 0.05 mm reaches x = -0.037 mm.
        var profile = MachineProfile.Default with { Calibration = new AxisCalibration { SquarenessDegrees = -0.5 } };

        var sheared = GeometryResolver.Resolve(SizeSpec.Width(10), 1000, 1000, new OriginMm(0.05, 5), profile);
        var square = GeometryResolver.Resolve(SizeSpec.Width(10), 1000, 1000, new OriginMm(0.05, 5), MachineProfile.Default);

        Assert.True(square.FitsTravel);
        Assert.False(sheared.FitsTravel);
        var left = sheared.Geometry.StageBounds().Left * sheared.Geometry.MicrostepUm / 1000;
        Assert.Equal(0.05 - (10 * Math.Tan(0.5 * Math.PI / 180)), left, 4);
    }
}
