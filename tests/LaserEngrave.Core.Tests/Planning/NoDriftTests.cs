using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Planning;

public class NoDriftTests
{
    // Seed 000's example: 10 mm over 180 px on the T-LA = 10000 / (180 x 127/1280) = 640000/1143 microsteps per pixel,
    // and an origin of 1 mm = 1280000/127 = 11520000/1143 microsteps. Every edge is a multiple of 1/1143 (odd), so
    // no edge is ever a rounding tie and the exact answer is unambiguous.
    private const double Pitch = 640000.0 / 1143;
    private const double OriginX = 1280000.0 / 127;

    [Theory]
    [InlineData(PlanStrategy.Optimized)]
    [InlineData(PlanStrategy.Paper)]
    public void Moves_AMillionRunsAtANonIntegerPitch_LastEdgesAreStillExactlyTheFormula(PlanStrategy strategy)
    {
        // Alternate pixels over the widest mask: 524288 black runs per row, two rows: 1048576 burn runs.
        var mask = new BitMask(BitMask.MaxSide, 2);
        for (var y = 0; y < mask.Height; y++)
        {
            mask.Row(y).Fill(0x5555_5555_5555_5555UL);
        }

        var geometry = new JobGeometry(mask.Width, mask.Height, Pitch, OriginX, 0, TestMasks.Microstep, long.MaxValue / 4, long.MaxValue / 4);
        var plan = new RasterPlan(mask, geometry, new PlanOptions { Strategy = strategy, Bidirectional = false });
        var checker = new EdgeChecker();
        plan.Visit(ref checker);

        Assert.Equal(0, checker.Mismatches);
        Assert.True(checker.BurnRuns >= 1_000_000, $"{checker.BurnRuns} runs");
        Assert.Equal(Exact(BitMask.MaxSide - 2), checker.LastBurnStart);
        Assert.Equal(Exact(BitMask.MaxSide - 1), checker.LastBurnEnd);
    }

    [Fact]
    public void EdgeX_AMillionColumnsIn_DiffersFromAddingUpRoundedSteps()
    {
        // The error this guards against: adding round(p) = 560 per pixel drifts by 0.07 microsteps per pixel.
        var geometry = new JobGeometry(BitMask.MaxSide, 1, Pitch, OriginX, 0, TestMasks.Microstep, long.MaxValue / 4, long.MaxValue / 4);
        long column = 1_000_000;
        Assert.Equal(Exact(column), geometry.EdgeX(column));
        Assert.NotEqual(geometry.EdgeX(0) + (column * (long)Math.Round(Pitch)), geometry.EdgeX(column));
    }

    /// <summary>round(ox + c p) in decimal from the exact fractions: (11520000 + 640000 c) / 1143.</summary>
    private static long Exact(long column) =>
        (long)Math.Round((11_520_000m + (640_000m * column)) / 1143m, MidpointRounding.AwayFromZero);

    private struct EdgeChecker : IMoveVisitor
    {
        public long BurnRuns;
        public long Mismatches;
        public long LastBurnStart;
        public long LastBurnEnd;

        public void Visit(in Move move)
        {
            if (move.Kind != MoveKind.Burn)
            {
                return;
            }

            // Black runs are the even columns: [2k, 2k + 1).
            var column = 2 * BurnRuns++ % BitMask.MaxSide;
            if (move.X0 != Exact(column) || move.X1 != Exact(column + 1))
            {
                Mismatches++;
            }

            LastBurnStart = move.X0;
            LastBurnEnd = move.X1;
        }
    }
}
