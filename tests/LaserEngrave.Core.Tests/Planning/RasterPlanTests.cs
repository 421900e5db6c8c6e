using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Planning;

public class RasterPlanTests
{
    private static readonly string[] ThreeRows = [".##.", "....", "#..#"];

    private static Move Travel(long x0, long y0, long x1, long y1, int row) => new(MoveKind.Travel, x0, y0, x1, y1, row);

    private static Move Burn(long x0, long x1, long y, int row) => new(MoveKind.Burn, x0, y, x1, y, row);

    private static Move Overscan(long x0, long x1, long y, int row) => new(MoveKind.Overscan, x0, y, x1, y, row);

    private static Move Travel(long x0, long x1, long y, int row) => new(MoveKind.Travel, x0, y, x1, y, row);

    [Fact]
    public void Moves_Paper_EveryRunOfEveryRowLeftToRightWithATravelBack()
    {
        var mask = TestMasks.FromRows(ThreeRows);
        var plan = new RasterPlan(mask, TestMasks.Geometry(mask), new PlanOptions { Strategy = PlanStrategy.Paper });

        // Pitch 1000 microsteps at the origin: row r burns along y = 1000 r + 500, column c starts at x = 1000 c.
        Move[] expected =
        [
            Travel(0, 1000, 500, 0), Burn(1000, 3000, 500, 0), Travel(3000, 4000, 500, 0),
            Travel(4000, 500, 0, 1500, 1), Travel(0, 4000, 1500, 1),
            Travel(4000, 1500, 0, 2500, 2), Burn(0, 1000, 2500, 2), Travel(1000, 3000, 2500, 2), Burn(3000, 4000, 2500, 2),
        ];
        Assert.Equal(expected, plan.Moves());
    }

    [Fact]
    public void Moves_OptimizedSerpentine_SkipsBlankRowsAndWhiteEndsAndReversesEveryOtherRow()
    {
        var mask = TestMasks.FromRows(ThreeRows);
        var plan = new RasterPlan(mask, TestMasks.Geometry(mask));

        Move[] expected =
        [
            Burn(1000, 3000, 500, 0),
            Travel(3000, 500, 4000, 2500, 2), Burn(4000, 3000, 2500, 2), Travel(3000, 1000, 2500, 2), Burn(1000, 0, 2500, 2),
        ];
        Assert.Equal(expected, plan.Moves());
    }

    [Fact]
    public void Moves_OptimizedUnidirectional_EveryRowLeftToRight()
    {
        var mask = TestMasks.FromRows(ThreeRows);
        var plan = new RasterPlan(mask, TestMasks.Geometry(mask), new PlanOptions { Bidirectional = false });

        Move[] expected =
        [
            Burn(1000, 3000, 500, 0),
            Travel(3000, 500, 0, 2500, 2), Burn(0, 1000, 2500, 2), Travel(1000, 3000, 2500, 2), Burn(3000, 4000, 2500, 2),
        ];
        Assert.Equal(expected, plan.Moves());
    }

    [Fact]
    public void Moves_Overscan_RunsUpAndOutAndCrossesShortGapsAtBurnSpeed()
    {
        var mask = TestMasks.FromRows("#.#......#");
        var options = new PlanOptions { OverscanMm = StageUnits.MicrostepsToMm(500, TestMasks.Microstep) };
        var plan = new RasterPlan(mask, TestMasks.Geometry(mask, ox: 10_000), options);

        // The 1000-microstep gap is no longer than two overscans, so it is one overscan; the 6000-microstep gap is not.
        Move[] expected =
        [
            Overscan(9500, 10_000, 500, 0), Burn(10_000, 11_000, 500, 0),
            Overscan(11_000, 12_000, 500, 0), Burn(12_000, 13_000, 500, 0),
            Overscan(13_000, 13_500, 500, 0), Travel(13_500, 18_500, 500, 0), Overscan(18_500, 19_000, 500, 0), Burn(19_000, 20_000, 500, 0),
            Overscan(20_000, 20_500, 500, 0),
        ];
        Assert.Equal(500, plan.OverscanMicrosteps);
        Assert.Equal(expected, plan.Moves());
        Assert.Empty(plan.Warnings);
    }

    [Fact]
    public void Moves_OverscanPastTheTravel_IsShortenedAndWarned()
    {
        var mask = TestMasks.FromRows("#........#");
        var options = new PlanOptions { OverscanMm = StageUnits.MicrostepsToMm(500, TestMasks.Microstep) };
        var plan = new RasterPlan(mask, TestMasks.Geometry(mask, ox: 200, travel: 10_500), options);

        Move[] expected =
        [
            Overscan(0, 200, 500, 0), Burn(200, 1200, 500, 0),
            Overscan(1200, 1700, 500, 0), Travel(1700, 8700, 500, 0), Overscan(8700, 9200, 500, 0), Burn(9200, 10_200, 500, 0),
            Overscan(10_200, 10_500, 500, 0),
        ];
        Assert.Equal(expected, plan.Moves());
        Assert.Equal(JobWarningKind.OverscanClamped, Assert.Single(plan.Warnings).Kind);
    }

    [Fact]
    public void Moves_PaperWithOverscanAndBidirectional_IgnoresBoth()
    {
        var mask = TestMasks.FromRows(ThreeRows);
        var plain = new RasterPlan(mask, TestMasks.Geometry(mask, ox: 5000), new PlanOptions { Strategy = PlanStrategy.Paper });
        var withOptions = new RasterPlan(
            mask,
            TestMasks.Geometry(mask, ox: 5000),
            new PlanOptions { Strategy = PlanStrategy.Paper, Bidirectional = true, OverscanMm = 0.2 });
        Assert.Equal(plain.Moves(), withOptions.Moves());
    }

    [Fact]
    public void Moves_BlankMask_OptimizedHasNoMovesPaperScansEveryRow()
    {
        var mask = TestMasks.FromRows("...", "...");
        Assert.Empty(new RasterPlan(mask, TestMasks.Geometry(mask)).Moves());
        var paper = new RasterPlan(mask, TestMasks.Geometry(mask), new PlanOptions { Strategy = PlanStrategy.Paper });
        Assert.Equal([0, 1, 1], paper.Moves().Select(m => m.Row));
    }

    [Fact]
    public void Moves_FromRow_IsTheTailOfTheWholeSequence()
    {
        var mask = TestMasks.FromRows("#.#.", "....", ".##.", "#...", "....");
        var plan = new RasterPlan(mask, TestMasks.Geometry(mask));
        var all = plan.Moves().ToList();
        for (var row = 0; row <= mask.Height; row++)
        {
            var from = all.FindIndex(m => m.Row >= row);
            Assert.Equal(from < 0 ? [] : all.Skip(from), plan.Moves(row));
        }
    }

    [Fact]
    public void Rows_IndexesEachVisitedRowsMoves()
    {
        var mask = TestMasks.FromRows("#.#.", "....", ".##.", "#...", "....");
        var plan = new RasterPlan(mask, TestMasks.Geometry(mask));
        var all = plan.Moves().ToList();
        var rows = plan.Rows().ToList();

        Assert.Equal([0, 2, 3], rows.Select(r => r.Row));
        Assert.Equal([true, false, true], rows.Select(r => r.LeftToRight));
        Assert.Equal(all.Count, rows.Sum(r => r.MoveCount));
        foreach (var row in rows)
        {
            Assert.All(all.Skip((int)row.FirstMoveIndex).Take(row.MoveCount), m => Assert.Equal(row.Row, m.Row));
        }
    }

    [Fact]
    public void Moves_LargePlan_StreamsARowAtATimeInsteadOfBuildingThePlan()
    {
        // 200 rows of 10000 one-pixel runs: about 4 million moves, some 190 MB if held whole.
        var mask = new BitMask(20_000, 200);
        for (var y = 0; y < mask.Height; y++)
        {
            mask.Row(y).Fill(0x5555_5555_5555_5555UL);
        }

        mask.ClearPadding();
        var plan = new RasterPlan(mask, TestMasks.Geometry(mask, pitch: 10));
        var before = GC.GetAllocatedBytesForCurrentThread();
        var first = plan.Moves().Take(3).ToList();
        var allocated = GC.GetAllocatedBytesForCurrentThread() - before;

        Assert.Equal(3, first.Count);
        Assert.True(allocated < 4_000_000, $"{allocated} bytes allocated for the first three moves");
    }

    [Fact]
    public void Constructor_MaskAndGeometryOfDifferentSizes_Throws()
    {
        var mask = TestMasks.FromRows("##");
        var other = TestMasks.FromRows("###");
        var ex = Assert.Throws<PlanException>(() => new RasterPlan(mask, TestMasks.Geometry(other)));
        Assert.Contains("2 x 1", ex.Message, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData(-1.0)]
    [InlineData(double.NaN)]
    [InlineData(double.PositiveInfinity)]
    public void Constructor_UnusableOverscan_Throws(double overscanMm)
    {
        var mask = TestMasks.FromRows("##");
        Assert.Throws<PlanException>(() => new RasterPlan(mask, TestMasks.Geometry(mask), new PlanOptions { OverscanMm = overscanMm }));
    }

    [Fact]
    public void ComputeStatistics_SerpentineExample_CountsRunsAndLengths()
    {
        var mask = TestMasks.FromRows(ThreeRows);
        var stats = new RasterPlan(mask, TestMasks.Geometry(mask)).ComputeStatistics(ProcessSettings.Default);

        // Burns of 2000, 1000 and 1000 microsteps; travels: the diagonal (1000, 2000) and the 2000 gap.
        Assert.Equal(2, stats.Rows);
        Assert.Equal(5, stats.Moves);
        Assert.Equal(3, stats.BurnRuns);
        Assert.Equal(4000 * TestMasks.Microstep / 1000, stats.BurnLengthMm, 12);
        Assert.Equal((Math.Sqrt(5_000_000) + 2000) * TestMasks.Microstep / 1000, stats.TravelLengthMm, 12);
        Assert.Equal(0, stats.OverscanLengthMm);

        // On, off for the travel, on, off for the gap, on, and off at the end.
        Assert.Equal(6, stats.LaserSwitches);
    }

    [Fact]
    public void ComputeStatistics_Paper_CountsEveryRow()
    {
        var mask = TestMasks.FromRows(ThreeRows);
        var stats = new RasterPlan(mask, TestMasks.Geometry(mask), new PlanOptions { Strategy = PlanStrategy.Paper })
            .ComputeStatistics(ProcessSettings.Default);
        Assert.Equal(3, stats.Rows);
        Assert.Equal(9, stats.Moves);
        Assert.Equal(0, stats.SpeedChanges);
    }
}

public class ResumeWithinTests
{
    [Theory]
    [InlineData(true, 450.0, 400L, 4)]
    [InlineData(true, 400.0, 400L, 4)]
    [InlineData(true, 399.0, 300L, 3)]
    [InlineData(true, 150.0, null, null)]
    [InlineData(false, 450.0, 500L, 4)]
    [InlineData(false, 500.0, 500L, 4)]
    [InlineData(false, 650.0, 700L, 6)]
    [InlineData(false, 750.0, null, null)]
    public void ResumeWithin_BurnedPartWay_FirstPixelNotCompletelyBurnedAndItsColumn(bool leftToRight, double burnedUpTo, long? resumeX, int? column)
    {
        // Pitch 100 microsteps, one run over columns 2..7 (x 200..800).
        var mask = TestMasks.FromRows("..######..");
        var plan = new RasterPlan(mask, TestMasks.Geometry(mask, pitch: 100));
        var y = plan.Geometry.RowY(0);
        var burn = leftToRight ? new Move(MoveKind.Burn, 200, y, 800, y, 0) : new Move(MoveKind.Burn, 800, y, 200, y, 0);

        var found = plan.ResumeWithin(burn, burnedUpTo);

        Assert.Equal(resumeX, found?.ResumeX);
        Assert.Equal(column, found?.Column);
    }
}
