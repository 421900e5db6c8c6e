using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Preview;
using LaserEngrave.Core.Sweeps;

namespace LaserEngrave.Core.Tests.Preview;

/// <summary>
/// A dot job's run counts dots, its picture draws the raster plan's runs (issue 23: the stage shows what burned): after k
/// dots the moves marked burned are the runs holding those dots, and everything drawn before them.
/// </summary>
public sealed class StagePictureDotTests
{
    // Runs of every width, a blank row, single pixels one white pixel apart, a run at each edge of the image.
    private static readonly string[] Rows =
    [
        "##.###..#....#",
        "..............",
        ".#####...##...",
        "#............#",
        "..##.##.##.##.",
        "#.#.#.#.#.#.#.",
    ];

    private static BitMask Mask(string[] rows)
    {
        var mask = new BitMask(rows[0].Length, rows.Length);
        for (var y = 0; y < rows.Length; y++)
        {
            for (var x = 0; x < rows[y].Length; x++)
            {
                mask[x, y] = rows[y][x] == '#';
            }
        }

        return mask;
    }

    private static PreparedJob DotJob(BitMask mask, bool bidirectional = true, double dotPitchPixels = 0, PlanStrategy strategy = PlanStrategy.Optimized, double scanOffsetUm = 0)
    {
        var info = new ImageInfo("dots", ImageFormat.Bmp, 1, 2, mask.Width, mask.Height, 0, null, null, RowOrder.TopDown, "none", false);
        var spec = new JobSpec { ImagePath = "dots.bmp", Size = SizeSpec.Width(mask.Width * 0.05), Origin = new OriginMm(1, 1) };
        spec = spec with
        {
            Profile = scanOffsetUm == 0 ? spec.Profile : spec.Profile with { ScanOffsets = [new ScanOffset(spec.Process.BurnSpeedMmPerS, scanOffsetUm)] },
            Process = spec.Process with { Mode = PlanMode.Dots },
            Plan = spec.Plan with { Bidirectional = bidirectional, Strategy = strategy },
        };
        var job = PreparedJob.Prepare(spec, info, mask);
        if (dotPitchPixels == 0)
        {
            return job;
        }

        var pitch = (long)Math.Round(dotPitchPixels * job.Geometry.Geometry.PitchXMicrosteps);
        return PreparedJob.Prepare(spec with { Process = spec.Process with { DotPitchMicrosteps = pitch } }, info, mask);
    }

    // For each dot in program order, the index of the plan's burn move (the picture's) on its row that holds it.
    private static List<int> Holders(PreparedJob job)
    {
        var burns = job.Plan.Moves().Select((m, i) => (Move: m, Index: i)).Where(b => b.Move.Kind == MoveKind.Burn).ToLookup(b => b.Move.Row);
        return [.. job.Dots!.Program().Steps().Select(d => burns[d.Row].Single(b => Math.Min(b.Move.X0, b.Move.X1) <= d.X && d.X <= Math.Max(b.Move.X0, b.Move.X1)).Index)];
    }

    private static void AssertBurnedAreTheRunsHoldingTheDots(PreparedJob job)
    {
        var picture = new StagePicture(EngraveJob.Of(job));
        var holders = Holders(job);
        var burns = job.Plan.Moves().Select((m, i) => (Move: m, Index: i)).Where(b => b.Move.Kind == MoveKind.Burn).Select(b => b.Index).ToList();

        Assert.True(holders.Count > 0);
        Assert.Equal(0, picture.DrawnDone(0, 0));
        for (var k = 1; k <= holders.Count; k++)
        {
            var done = picture.DrawnDone(0, k);
            var held = holders.Take(k).ToHashSet();

            // Exactly the runs holding the first k dots are burned, and the last of them is the last move marked.
            Assert.Equal(held.Order(), burns.Where(b => b < done));
            Assert.Equal(held.Max() + 1, done);
        }

        Assert.Equal(holders.Max() + 1, picture.DrawnDone(0, holders.Count + 5));
    }

    [Fact]
    public void DrawnDone_DotJobAfterKDots_TheRunsHoldingThoseDots()
    {
        AssertBurnedAreTheRunsHoldingTheDots(DotJob(Mask(Rows)));
    }

    [Fact]
    public void DrawnDone_DotJobOneWay_TheRunsHoldingThoseDots()
    {
        AssertBurnedAreTheRunsHoldingTheDots(DotJob(Mask(Rows), bidirectional: false));
    }

    [Theory]
    [InlineData(0.3)]
    [InlineData(0.5)]
    [InlineData(1)]
    [InlineData(2)]
    [InlineData(2.5)]
    public void DrawnDone_DotPitchFinerOrCoarserThanThePixel_TheRunsHoldingThoseDots(double dotPitchPixels)
    {
        var job = DotJob(Mask(Rows), dotPitchPixels: dotPitchPixels);

        Assert.True(job.Dots!.DotPitchMicrosteps > 0);
        AssertBurnedAreTheRunsHoldingTheDots(job);
    }

    [Fact]
    public void DrawnDone_DotsMatchTheRunsOneByOne_EachRunsDotsMarkOnlyItself()
    {
        // A dot pitch of half a pixel puts two dots on every pixel: each run's dots, fired one after the other, mark that run.
        var job = DotJob(Mask(Rows), dotPitchPixels: 0.5);
        var picture = new StagePicture(EngraveJob.Of(job));
        var holders = Holders(job);

        Assert.True(holders.Count > Rows.Sum(r => r.Count(c => c == '#')));
        for (var k = 1; k < holders.Count; k++)
        {
            Assert.Equal(holders[k - 1] + 1, picture.DrawnDone(0, k));
        }
    }

    [Fact]
    public void DrawnDone_PaperPlanOfADotJob_EveryFiredDotsRunBurnedAndNeverLess()
    {
        // A paper plan scans every row left to right while the dots go serpentine: the marks cover every dot fired and never go back.
        var job = DotJob(Mask(Rows), strategy: PlanStrategy.Paper);
        var picture = new StagePicture(EngraveJob.Of(job));
        var holders = Holders(job);

        var before = 0L;
        for (var k = 1; k <= holders.Count; k++)
        {
            var done = picture.DrawnDone(0, k);
            Assert.True(done >= before);
            Assert.True(done > holders.Take(k).Max());
            before = done;
        }

        Assert.Equal(holders.Max() + 1, before);
    }

    [Fact]
    public void DrawnDone_DotJobPastTheCap_TheRunsHoldingTheDotsThenEveryMoveDrawn()
    {
        // One-pixel checks: a dot and a burn run on every other pixel, more moves than the page draws.
        var mask = new BitMask(500, 500);
        for (var y = 0; y < mask.Height; y++)
        {
            for (var x = y % 2; x < mask.Width; x += 2)
            {
                mask[x, y] = true;
            }
        }

        var job = DotJob(mask);
        var picture = new StagePicture(EngraveJob.Of(job));
        var holders = Holders(job);

        Assert.Equal(StagePicture.MaxDrawnMoves, picture.Drawn);
        var lastDrawn = holders.FindLastIndex(h => h < picture.Drawn);
        Assert.InRange(lastDrawn, 1000, holders.Count - 2);
        foreach (var k in new[] { 1, 2, 251, 1000, lastDrawn + 1 })
        {
            Assert.Equal(holders[k - 1] + 1, picture.DrawnDone(0, k));
        }

        Assert.Equal(picture.Drawn, picture.DrawnDone(0, lastDrawn + 2));
        Assert.Equal(picture.Drawn, picture.DrawnDone(0, holders.Count));
    }

    [Fact]
    public void New_DotJob_PictureStillThePlansMoves()
    {
        var job = DotJob(Mask(Rows));
        var picture = new StagePicture(EngraveJob.Of(job));

        Assert.Equal(StagePicture.PlanMoves(job).Bytes, picture.Moves);
        Assert.Null(picture.Parts[0].StrokeEnds);
    }

    [Theory]
    [InlineData(40)]
    [InlineData(-40)]
    public void DrawnDone_ReverseRowsShiftedByAScanOffset_TheSameRunsAsWithout(double scanOffsetUm)
    {
        // The offset shifts the right-to-left rows' burn runs (most of a 50 µm pixel here), not the dots: each dot still marks the run it was placed in.
        var plain = new StagePicture(EngraveJob.Of(DotJob(Mask(Rows))));
        var job = DotJob(Mask(Rows), scanOffsetUm: scanOffsetUm);
        var shifted = new StagePicture(EngraveJob.Of(job));
        var dots = job.Dots!.Program().Steps().Count();

        Assert.NotEqual(plain.Moves, shifted.Moves);
        Assert.Equal(plain.Drawn, shifted.Drawn);
        Assert.Equal(Enumerable.Range(0, dots + 1).Select(k => plain.DrawnDone(0, k)), Enumerable.Range(0, dots + 1).Select(k => shifted.DrawnDone(0, k)));
    }

    [Fact]
    public void DrawnDone_SweepOfDotCells_EachCellsDotsMarkItsOwnRuns()
    {
        var plan = SweepPlan.Build(new SweepSpec
        {
            Rows = SweepAxis.Parse("pulses-per-dot=1,3", "--rows"),
            Origin = new OriginMm(5, 5),
            CellMm = 0.5,
            PitchUm = 50,
            Labels = true,
            Process = ProcessSettings.Default with { Mode = PlanMode.Dots },
        });
        var picture = new StagePicture(SweepJob.Of(plan));
        var cell = plan.Cells[1].Job;
        var alone = new StagePicture(EngraveJob.Of(cell));
        var part = picture.Parts.Count - 1;

        Assert.NotNull(cell.Dots);
        Assert.Null(picture.Parts[0].DotMarks);
        Assert.NotNull(picture.Parts[part].DotMarks);
        foreach (var k in new long[] { 0, 1, 5, 30, 1000 })
        {
            Assert.Equal(picture.Parts[part].Start + alone.DrawnDone(0, k), picture.DrawnDone(part, k));
        }
    }
}
