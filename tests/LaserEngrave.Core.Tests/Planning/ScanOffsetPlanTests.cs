using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Planning;

public class ScanOffsetPlanTests
{
    // 100.4 microsteps of 0.09921875 µm: with the origin's 0.4 the edges sit at x.8, which rounds up once (the offset
    // rounded on its own, 100, and added to the rounded edge would give one microstep less).
    private const double OffsetMicrosteps = 100.4;
    private const double OffsetUm = OffsetMicrosteps * TestMasks.Microstep;

    private static readonly string[] Rows = ["..##....#.", ".###..##..", "..##....#.", "#........#"];

    private static List<Move> Burns(RasterPlan plan) => [.. plan.Moves().Where(m => m.Kind == MoveKind.Burn)];

    [Fact]
    public void Moves_Bidirectional_ReverseRowEdgesMoveByTheOffsetRoundedOnce_ForwardRowsDoNot()
    {
        var mask = TestMasks.FromRows(Rows);
        var geometry = TestMasks.Geometry(mask, pitch: 1000, ox: 20_000.4);
        var plain = Burns(new RasterPlan(mask, geometry));
        var shifted = Burns(new RasterPlan(mask, geometry, scanOffsetUm: OffsetUm));

        Assert.Equal(plain.Count, shifted.Count);
        for (var i = 0; i < plain.Count; i++)
        {
            var (before, after) = (plain[i], shifted[i]);
            Assert.Equal(before.Row, after.Row);
            Assert.Equal(before.Y0, after.Y0);
            if (before.X1 > before.X0)
            {
                // Left to right (rows 0 and 2): not touched.
                Assert.Equal(before, after);
            }
            else
            {
                // Right to left (rows 1 and 3): edge = round(ox + c p + offset), never round(ox + c p) + round(offset).
                var entryColumn = (before.X0 - 20_000) / 1000;
                var exitColumn = (before.X1 - 20_000) / 1000;
                Assert.Equal((long)Math.Round(20_000.4 + (entryColumn * 1000) + OffsetMicrosteps, MidpointRounding.AwayFromZero), after.X0);
                Assert.Equal((long)Math.Round(20_000.4 + (exitColumn * 1000) + OffsetMicrosteps, MidpointRounding.AwayFromZero), after.X1);
                Assert.Equal(before.X0 + 101, after.X0);
                Assert.Equal(before.X1 + 101, after.X1);
            }
        }

        Assert.Contains(plain, m => m.X1 < m.X0);
    }

    [Fact]
    public void Moves_NegativeOffset_ShiftsReverseRowsTowardsMinusX()
    {
        var mask = TestMasks.FromRows(Rows);
        var geometry = TestMasks.Geometry(mask, pitch: 1000, ox: 20_000);
        var reverse = Burns(new RasterPlan(mask, geometry, scanOffsetUm: -50 * TestMasks.Microstep)).Where(m => m.X1 < m.X0).ToList();

        Assert.NotEmpty(reverse);
        Assert.All(reverse, m =>
        {
            Assert.Equal(0, (m.X0 + 50 - 20_000) % 1000);
            Assert.Equal(0, (m.X1 + 50 - 20_000) % 1000);
        });
    }

    [Theory]
    [InlineData(PlanStrategy.Optimized, false)]
    [InlineData(PlanStrategy.Paper, true)]
    public void Moves_NoReverseRows_TheOffsetChangesNothing(PlanStrategy strategy, bool bidirectional)
    {
        var mask = TestMasks.FromRows(Rows);
        var geometry = TestMasks.Geometry(mask, pitch: 1000, ox: 20_000.4);
        var options = new PlanOptions { Strategy = strategy, Bidirectional = bidirectional };

        Assert.Equal(new RasterPlan(mask, geometry, options).Moves(), new RasterPlan(mask, geometry, options, OffsetUm).Moves());
    }

    [Fact]
    public void Moves_WithOverscan_TheWholeReverseRowShifts()
    {
        var mask = TestMasks.FromRows(Rows);
        var geometry = TestMasks.Geometry(mask, pitch: 1000, ox: 20_000);
        var options = new PlanOptions { OverscanMm = 0.05 };
        var plain = new RasterPlan(mask, geometry, options).Moves().Where(m => m.Row == 1 && m.Kind != MoveKind.Travel).ToList();
        var shifted = new RasterPlan(mask, geometry, options, 10 * TestMasks.Microstep).Moves().Where(m => m.Row == 1 && m.Kind != MoveKind.Travel).ToList();

        Assert.Equal(plain.Select(m => m with { X0 = m.X0 + 10, X1 = m.X1 + 10 }), shifted);
    }

    [Fact]
    public void Warnings_OffsetPastTheTravel_Warned_OnlyWhenRowsRunBothWays()
    {
        var mask = TestMasks.FromRows(Rows);
        var geometry = TestMasks.Geometry(mask, pitch: 1000, ox: 0);

        var warning = Assert.Single(new RasterPlan(mask, geometry, scanOffsetUm: -5).Warnings);
        Assert.Equal(JobWarningKind.OutsideTravel, warning.Kind);
        Assert.Contains("scan offset -5 µm moves the right-to-left rows past the stage travel at the left edge", warning.Message, StringComparison.Ordinal);
        Assert.Empty(new RasterPlan(mask, geometry, scanOffsetUm: 5).Warnings);
        Assert.Empty(new RasterPlan(mask, geometry, new PlanOptions { Bidirectional = false }, -5).Warnings);
    }

    [Fact]
    public void Constructor_OffsetNotFinite_Refused()
    {
        var mask = TestMasks.FromRows(Rows);

        var ex = Assert.Throws<PlanException>(() => new RasterPlan(mask, TestMasks.Geometry(mask), scanOffsetUm: double.NaN));

        Assert.Contains("scan offset NaN µm must be a finite number", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void RunEdgeX_ZeroOffset_IsTheUnshiftedEdgeBitForBit()
    {
        var geometry = new JobGeometry(50, 50, 1229.114653351258, 100_787.3, 50_393.7, TestMasks.Microstep, 604_724, 604_724);
        for (var c = 0; c <= 50; c++)
        {
            Assert.Equal(geometry.RunEdgeX(c, 7), geometry.RunEdgeX(c, 7, 0));
        }
    }
}
