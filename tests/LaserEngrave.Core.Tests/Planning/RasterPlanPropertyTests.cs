using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Planning;

/// <summary>Properties of every plan over random masks, sizes, origins and options (seeded, so a failure repeats).</summary>
public class RasterPlanPropertyTests
{
    private const int Iterations = 300;

    public static TheoryData<PlanStrategy, bool> Variants => new()
    {
        { PlanStrategy.Paper, false },
        { PlanStrategy.Optimized, true },
        { PlanStrategy.Optimized, false },
    };

    [Theory]
    [MemberData(nameof(Variants))]
    public void Moves_RandomMasks_BurnEveryBlackPixelOnceNoWhiteOneAndPutEveryEdgeOnTheFormula(PlanStrategy strategy, bool bidirectional)
    {
        var rng = new Random(7919 + (int)strategy + (bidirectional ? 100 : 0));
        for (var iteration = 0; iteration < Iterations; iteration++)
        {
            var job = RandomJob(rng, strategy, bidirectional);
            var (plan, edges) = (job.Plan, job.Edges);
            var mask = plan.Mask;
            var moves = plan.Moves().ToList();
            var burned = new int[mask.Width, mask.Height];
            var context = $"iteration {iteration}: {mask.Width} x {mask.Height}, pitch {plan.Geometry.PitchMicrosteps}, origin ({plan.Geometry.OriginXMicrosteps}, {plan.Geometry.OriginYMicrosteps}), overscan {plan.OverscanMicrosteps}";

            for (var i = 0; i < moves.Count; i++)
            {
                var move = moves[i];
                Assert.True(move.X0 != move.X1 || move.Y0 != move.Y1, $"{context}: move {i} goes nowhere");
                if (i > 0)
                {
                    Assert.True(move.X0 == moves[i - 1].X1 && move.Y0 == moves[i - 1].Y1, $"{context}: move {i} does not start where move {i - 1} ended");
                }

                if (move.Y0 != move.Y1)
                {
                    Assert.True(move.Kind == MoveKind.Travel, $"{context}: move {i} changes rows with the laser on or at burn speed");
                    Assert.Equal(edges.RowY[move.Row], move.Y1);
                    continue;
                }

                Assert.True(edges.RowY[move.Row] == move.Y0, $"{context}: move {i} on row {move.Row} is at y {move.Y0}, the formula says {edges.RowY[move.Row]}");
                if (move.Kind == MoveKind.Burn)
                {
                    var c0 = edges.Column(Math.Min(move.X0, move.X1), context);
                    var c1 = edges.Column(Math.Max(move.X0, move.X1), context);
                    for (var c = c0; c < c1; c++)
                    {
                        burned[c, move.Row]++;
                    }
                }
                else
                {
                    AssertCrossesNoBlackPixel(mask, edges, move, context);
                }
            }

            for (var y = 0; y < mask.Height; y++)
            {
                for (var x = 0; x < mask.Width; x++)
                {
                    Assert.True(burned[x, y] == (mask[x, y] ? 1 : 0), $"{context}: pixel ({x}, {y}) is {(mask[x, y] ? "black" : "white")} and burned {burned[x, y]} times");
                }
            }
        }
    }

    [Theory]
    [MemberData(nameof(Variants))]
    public void Moves_RandomMasks_VisitTheRightRowsInTheRightDirections(PlanStrategy strategy, bool bidirectional)
    {
        var rng = new Random(104729 + (int)strategy + (bidirectional ? 100 : 0));
        for (var iteration = 0; iteration < Iterations; iteration++)
        {
            var plan = RandomJob(rng, strategy, bidirectional).Plan;
            var mask = plan.Mask;
            var moves = plan.Moves().ToList();
            var visited = moves.Select(m => m.Row).Distinct().ToList();

            if (strategy == PlanStrategy.Paper)
            {
                Assert.Equal(Enumerable.Range(0, mask.Height), visited);
                Assert.DoesNotContain(moves, m => m.Kind == MoveKind.Overscan);
                Assert.All(moves.Where(m => m.Y0 == m.Y1), m => Assert.True(m.X1 > m.X0, "paper scans left to right"));
                foreach (var row in visited)
                {
                    // Every row is scanned whole: its moves along the row line cover the image edge to edge.
                    var along = moves.Where(m => m.Row == row && m.Y0 == m.Y1).ToList();
                    Assert.Equal(plan.Geometry.EdgeX(0), along[0].X0);
                    Assert.Equal(plan.Geometry.EdgeX(mask.Width), along[^1].X1);
                }

                continue;
            }

            var nonBlank = Enumerable.Range(0, mask.Height).Where(y => mask.CountSet(y) > 0);
            Assert.Equal(nonBlank, visited);
            for (var k = 0; k < visited.Count; k++)
            {
                var rightwards = !bidirectional || k % 2 == 0;
                Assert.All(moves.Where(m => m.Row == visited[k] && m.Y0 == m.Y1), m => Assert.Equal(rightwards, m.X1 > m.X0));
            }

            // Each run is burned whole in one move: burn moves never touch end to end.
            for (var i = 1; i < moves.Count; i++)
            {
                Assert.False(moves[i].Kind == MoveKind.Burn && moves[i - 1].Kind == MoveKind.Burn, "two burns back to back");
            }
        }
    }

    [Fact]
    public void Moves_RandomMasksWithOverscan_RunUpAndRunOutAtFullLengthUnlessTheTravelEnds()
    {
        var rng = new Random(31337);
        for (var iteration = 0; iteration < Iterations; iteration++)
        {
            var plan = RandomJob(rng, PlanStrategy.Optimized, rng.Next(2) == 0, forceOverscan: true).Plan;
            var o = plan.OverscanMicrosteps;
            var travel = plan.Geometry.TravelXMicrosteps;
            var moves = plan.Moves().ToList();
            for (var i = 0; i < moves.Count; i++)
            {
                if (moves[i].Kind != MoveKind.Burn)
                {
                    continue;
                }

                // A run-up or run-out is missing only where the burn edge sits on the end of the travel (no room at all).
                var burn = moves[i];
                var before = i > 0 ? moves[i - 1] : default;
                var after = i + 1 < moves.Count ? moves[i + 1] : default;
                if (i == 0 || before.Kind != MoveKind.Overscan)
                {
                    Assert.True(burn.X0 == 0 || burn.X0 == travel, $"iteration {iteration}: no run-up before a burn at {burn.X0}");
                }
                else
                {
                    Assert.True(
                        before.LengthX == o || before.X0 == 0 || before.X0 == travel || (i >= 2 && moves[i - 2].Kind == MoveKind.Burn),
                        $"iteration {iteration}: run-up of {before.LengthX} microsteps, overscan {o}");
                }

                if (i + 1 == moves.Count || after.Kind != MoveKind.Overscan)
                {
                    Assert.True(burn.X1 == 0 || burn.X1 == travel, $"iteration {iteration}: no run-out after a burn at {burn.X1}");
                }
                else
                {
                    Assert.True(
                        after.LengthX == o || after.X1 == 0 || after.X1 == travel || (i + 2 < moves.Count && moves[i + 2].Kind == MoveKind.Burn),
                        $"iteration {iteration}: run-out of {after.LengthX} microsteps, overscan {o}");
                }
            }

            Assert.All(moves, m => Assert.InRange(Math.Min(m.X0, m.X1), 0, travel));
            Assert.All(moves, m => Assert.InRange(Math.Max(m.X0, m.X1), 0, travel));
        }
    }

    [Fact]
    public void Plan_RandomMasks_StatisticsResumeAndRowsAgreeWithTheMoves()
    {
        var rng = new Random(271828);
        for (var iteration = 0; iteration < Iterations; iteration++)
        {
            var strategy = rng.Next(3) == 0 ? PlanStrategy.Paper : PlanStrategy.Optimized;
            var plan = RandomJob(rng, strategy, rng.Next(2) == 0).Plan;
            var moves = plan.Moves().ToList();
            var process = ProcessSettings.Default with { BurnSpeedMmPerS = 0.5 + rng.NextDouble(), TravelSpeedMmPerS = 2 + rng.NextDouble() };

            var stats = plan.ComputeStatistics(process);
            var estimator = new PlanEstimator(process, strategy, plan.Geometry.MicrostepUm);
            foreach (var move in moves)
            {
                estimator.Add(move);
            }

            estimator.Finish();
            Assert.Equal(moves.Count, stats.Moves);
            Assert.Equal(moves.Count(m => m.Kind == MoveKind.Burn), stats.BurnRuns);
            Assert.Equal(StageUnits.MicrostepsToMm(moves.Where(m => m.Kind == MoveKind.Burn).Sum(m => m.LengthX), plan.Geometry.MicrostepUm), stats.BurnLengthMm, 9);
            Assert.Equal(estimator.ElapsedSeconds, stats.EngravingSeconds, 9);
            Assert.Equal(estimator.LaserSwitches, stats.LaserSwitches);

            var fromRow = rng.Next(plan.Mask.Height + 1);
            var tail = moves.FindIndex(m => m.Row >= fromRow);
            Assert.Equal(tail < 0 ? [] : moves.Skip(tail), plan.Moves(fromRow));

            var rows = plan.Rows().ToList();
            Assert.Equal(stats.Rows, rows.Count);
            Assert.Equal(moves.Count, rows.Sum(r => r.MoveCount));
            Assert.All(rows, r => Assert.Equal(r.Row, moves[(int)r.FirstMoveIndex].Row));
        }
    }

    private static void AssertCrossesNoBlackPixel(BitMask mask, Edges edges, Move move, string context)
    {
        long a = Math.Min(move.X0, move.X1), b = Math.Max(move.X0, move.X1);
        for (var c = 0; c < mask.Width; c++)
        {
            if (mask[c, move.Row] && Math.Max(a, edges.X[c]) < Math.Min(b, edges.X[c + 1]))
            {
                Assert.Fail($"{context}: a {move.Kind} from {move.X0} to {move.X1} on row {move.Row} crosses black pixel {c}");
            }
        }
    }

    /// <summary>A random job whose pitch and origin are exact in both double and decimal (multiples of 1/1024 and 1/256), so the decimal formula is the truth, ties included.</summary>
    private static (RasterPlan Plan, Edges Edges) RandomJob(Random rng, PlanStrategy strategy, bool bidirectional, bool forceOverscan = false)
    {
        var width = 1 + rng.Next(rng.Next(4) == 0 ? 300 : 60);
        var height = 1 + rng.Next(25);
        var mask = TestMasks.Random(rng, width, height);
        var pitch = (1024 + rng.Next(rng.Next(3) == 0 ? 2048 : 64 * 1024)) / 1024m;
        var ox = rng.Next(256 * 20_000) / 256m;
        var oy = rng.Next(256 * 20_000) / 256m;
        var edges = new Edges(width, height, pitch, ox, oy);

        var overscanMicrosteps = forceOverscan || rng.Next(2) == 0 ? rng.Next(1, 3 * (int)Math.Ceiling(pitch) + 10) : 0;
        var overscanMm = StageUnits.MicrostepsToMm(overscanMicrosteps, TestMasks.Microstep);
        var right = edges.X[width];
        var travel = rng.Next(3) == 0 ? right + rng.Next(2 * overscanMicrosteps + 1) : right + 1_000_000;

        var geometry = new JobGeometry(width, height, (double)pitch, (double)ox, (double)oy, TestMasks.Microstep, travel, 1L << 40);
        var options = new PlanOptions { Strategy = strategy, Bidirectional = bidirectional, OverscanMm = overscanMm };
        return (new RasterPlan(mask, geometry, options), edges);
    }

    /// <summary>The edge formula recomputed independently in decimal: x(c) = round(ox + c p), y(r) = round(oy + (r + 0.5) p), half away from zero.</summary>
    private sealed class Edges
    {
        private readonly Dictionary<long, int> _columns = [];

        public Edges(int width, int height, decimal pitch, decimal ox, decimal oy)
        {
            X = new long[width + 1];
            for (var c = 0; c <= width; c++)
            {
                X[c] = (long)Math.Round(ox + (c * pitch), MidpointRounding.AwayFromZero);
                _columns[X[c]] = c;
            }

            RowY = new long[height];
            for (var r = 0; r < height; r++)
            {
                RowY[r] = (long)Math.Round(oy + ((r + 0.5m) * pitch), MidpointRounding.AwayFromZero);
            }
        }

        public long[] X { get; }

        public long[] RowY { get; }

        public int Column(long x, string context) =>
            _columns.TryGetValue(x, out var column) ? column : throw new Xunit.Sdk.XunitException($"{context}: a burn ends at x {x}, which is no pixel edge of the formula");
    }
}
