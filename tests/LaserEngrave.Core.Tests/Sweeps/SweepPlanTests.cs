using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Sweeps;

namespace LaserEngrave.Core.Tests.Sweeps;

/// <summary>A sweep's layout and each cell's values, checked by hand.</summary>
public class SweepPlanTests
{
    private static SweepSpec Spec(string rows, string? columns = null) => new()
    {
        Rows = SweepAxis.Parse(rows, "--rows"),
        Columns = columns is null ? null : SweepAxis.Parse(columns, "--columns"),
        Origin = new OriginMm(5, 5),
        CellMm = 1,
        SpacingMm = 0.5,
        PitchUm = 50,
    };

    [Fact]
    public void Build_SpeedRowsFrequencyColumns_EachCellItsValuesAndPlace()
    {
        var plan = SweepPlan.Build(Spec("speed=0.5,1,2", "frequency=500,1000"));

        Assert.Equal(6, plan.Cells.Count);
        var cell = plan.Cells[3];

        // Row 2, column 2: 1 mm/s at 1000 Hz, 1.5 mm right of and 1.5 mm below the first cell at 5, 5 mm.
        Assert.Equal((1, 1), (cell.Row, cell.Column));
        Assert.Equal(new Dictionary<string, double> { ["speedMmPerS"] = 1, ["frequencyHz"] = 1000 }, cell.Parameters);
        Assert.Equal((6.5, 6.5), (cell.OriginXMm, cell.OriginYMm));
        Assert.Equal((1.0, 1000.0), (cell.Job.Spec.Process.BurnSpeedMmPerS, cell.Job.Spec.Process.LaserFrequencyHz));

        // 1 mm at 50 µm: 20 x 20 pixels, all black; 50 µm / (1 mm/s / 1000 Hz) = 50 pulses a pixel.
        Assert.Equal((20, 20, 400L), (cell.Job.Mask.Width, cell.Job.Mask.Height, cell.Job.Mask.CountSet()));
        Assert.Equal(50, cell.Job.Pulses.PulsesPerPixel!.Value, 9);
        Assert.Equal(12.5, plan.Cells[4].Job.Pulses.PulsesPerPixel!.Value, 9);
        Assert.Null(plan.Labels);
        Assert.Equal(plan.Cells.Sum(c => c.Job.Statistics.EngravingSeconds), plan.EngravingSeconds, 9);

        // The whole sweep: the first cell's preparation (homing from the far end), then each cell's preflight and travel.
        Assert.InRange(plan.EstimatedSeconds - plan.EngravingSeconds, plan.Cells[0].Job.Statistics.PreparationSeconds, plan.Cells[0].Job.Statistics.PreparationSeconds + (5 * 1.5));
    }

    [Fact]
    public void Build_PitchAndPassesSwept_CellsSizedByTheirPitchBurnedTheirPasses()
    {
        var plan = SweepPlan.Build(Spec("pitch=25,100", "passes=1,3"));

        Assert.Equal((40, 1), (plan.Cells[0].Job.Mask.Width, plan.Cells[0].Job.Spec.Passes));
        Assert.Equal((10, 3), (plan.Cells[3].Job.Mask.Width, plan.Cells[3].Job.Spec.Passes));
        Assert.Equal(100, plan.Cells[3].Job.Geometry.PitchUm, 9);
        Assert.Equal(
            plan.Cells.Sum(c => c.Job.Statistics.EngravingSeconds * c.Job.Spec.Passes),
            plan.EngravingSeconds,
            9);
    }

    [Theory]
    [InlineData(PlanMode.Raster)]
    [InlineData(PlanMode.Dots)]
    public void Statistics_Ends_AreThePlansFirstAndLastPositions(PlanMode mode)
    {
        // The sweep's estimate chains cells from these ends without walking the plans again.
        var plan = SweepPlan.Build(Spec("speed=1,2") with
        {
            Pattern = mode == PlanMode.Dots ? SweepPattern.Dots : SweepPattern.Lines,
            Process = ProcessSettings.Default with { Mode = mode },
        });

        foreach (var job in plan.Jobs())
        {
            var ends = Assert.NotNull(job.Statistics.Ends);
            if (job.Dots is { } dots)
            {
                Assert.Equal((dots.Dots().First().X, dots.Dots().First().Y), ends.First);
                Assert.Equal((dots.Dots().Last().X, dots.Dots().Last().Y), ends.Last);
            }
            else
            {
                Assert.Equal((job.Plan.Moves().First().X0, job.Plan.Moves().First().Y0), ends.First);
                Assert.Equal((job.Plan.Moves().Last().X1, job.Plan.Moves().Last().Y1), ends.Last);
            }
        }
    }

    [Fact]
    public void Build_PulsesPerDotInDotMode_DotArrayCellsFireTheirCount()
    {
        var spec = Spec("pulses-per-dot=1,10") with
        {
            Pattern = SweepPattern.Dots,
            Process = ProcessSettings.Default with { Mode = PlanMode.Dots },
        };

        var plan = SweepPlan.Build(spec);

        var cell = plan.Cells[1];
        Assert.Equal(10, cell.Job.Spec.Process.PulsesPerDot);
        Assert.Equal(100, cell.Job.Dots!.Estimate.Dots);
        Assert.Equal(1000, cell.Job.Dots.Estimate.Pulses);
    }

    [Theory]
    [InlineData(SweepPattern.Square, "####|####|####|####")]
    [InlineData(SweepPattern.Lines, "####|....|####|....")]
    [InlineData(SweepPattern.Dots, "#.#.|....|#.#.|....")]
    public void CellMask_Pattern_ItsPixels(SweepPattern pattern, string expected)
    {
        var mask = SweepPlan.CellMask(pattern, 4);

        Assert.Equal(expected, string.Join('|', Enumerable.Range(0, 4).Select(y => new string([.. Enumerable.Range(0, 4).Select(x => mask[x, y] ? '#' : '.')]))));
    }

    [Fact]
    public void Build_Labels_CellsMovedPastTheLabelStripsAndEveryDigitBurned()
    {
        var plan = SweepPlan.Build(Spec("speed=0.5,1", "frequency=500,1000") with { Labels = true });

        // Glyphs 0.4 mm tall: pixels of 80 µm; the widest row label "0.5" is 11 px = 0.88 mm, then the 0.5 mm spacing;
        // the column labels 5 px = 0.4 mm tall, then 0.5 mm.
        var labels = Assert.IsType<Core.Jobs.PreparedJob>(plan.Labels);
        Assert.Equal(80, labels.Geometry.PitchUm, 9);
        Assert.Equal(5 + 0.88 + 0.5, plan.GridXMm, 9);
        Assert.Equal(5 + 0.4 + 0.5, plan.GridYMm, 9);
        Assert.Equal((plan.GridXMm, plan.GridYMm), (plan.Cells[0].OriginXMm, plan.Cells[0].OriginYMm));
        Assert.Equal(PlanMode.Raster, labels.Spec.Process.Mode);

        // Every glyph of "0.5" and "1" beside the rows, "500" and "1000" over the columns, none cut off.
        var expected = new[] { "0.5", "1", "500", "1000" }.Sum(Pixels);
        Assert.Equal(expected, labels.Mask.CountSet());

        static long Pixels(string text)
        {
            var mask = new BitMask(TinyFont.Width(text), TinyFont.GlyphHeight);
            TinyFont.Draw(mask, text, 0, 0);
            return mask.CountSet();
        }
    }

    [Fact]
    public void TinyFont_Digits_ThreeByFiveGlyphs()
    {
        var mask = new BitMask(TinyFont.Width("10"), 5);

        TinyFont.Draw(mask, "10", 0, 0);

        Assert.Equal(7, mask.Width);
        var rows = Enumerable.Range(0, 5).Select(y => new string([.. Enumerable.Range(0, 7).Select(x => mask[x, y] ? '#' : '.')]));
        Assert.Equal([".#..###", "##..#.#", ".#..#.#", ".#..#.#", "###.###"], rows);
    }

    [Theory]
    [InlineData("speed", "expected PARAMETER=V1,V2")]
    [InlineData("colour=1,2", "'colour' is not a sweep parameter")]
    [InlineData("speed=1,x", "'x' is not a number")]
    [InlineData("passes=1.5", "passes takes whole numbers")]
    [InlineData("speed=NaN", "'NaN' is not a number")]
    [InlineData("focus=-100..100:0", "the step must be above 0")]
    [InlineData("focus=-100..100", "expected FROM..TO:STEP")]
    [InlineData("focus=-1000..1000:10", "201 values, at most 50")]
    [InlineData("passes=1..4:0.5", "passes takes whole numbers")]
    public void Parse_Bad_OneLineNamingIt(string text, string fragment)
    {
        var ex = Assert.Throws<SweepException>(() => SweepAxis.Parse(text, "--rows"));

        Assert.Contains(fragment, ex.Message, StringComparison.Ordinal);
        Assert.StartsWith("--rows ", ex.Message, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("speed=0.5,10", null, "speed 10 mm/s: outside what the stage takes")]
    [InlineData("frequency=0", null, "outside what the laser gate takes")]
    [InlineData("passes=0,2", null, "passes 0: must be 1..100")]
    [InlineData("pulses-per-dot=3", null, "add --mode dots")]
    [InlineData("pitch=0.01", null, "below one microstep")]
    [InlineData("pitch=2000", null, "(the cell)")]
    [InlineData("speed=1", "speed=2", "both vary speed")]
    public void Build_BadValue_RefusedNamingIt(string rows, string? columns, string fragment)
    {
        var ex = Assert.Throws<SweepException>(() => SweepPlan.Build(Spec(rows, columns)));

        Assert.Contains(fragment, ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Build_PastTheTravel_RefusedNamingTheCell()
    {
        var ex = Assert.Throws<SweepException>(() => SweepPlan.Build(Spec("speed=1,2,3") with { Origin = new OriginMm(10, 58) }));

        Assert.Contains("cell row 2, column 1", ex.Message, StringComparison.Ordinal);
        Assert.Contains("past the stage travel", ex.Message, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("focus=-200..200:50", new[] { -200.0, -150, -100, -50, 0, 50, 100, 150, 200 })]
    [InlineData("focus=100..-100:100", new[] { 100.0, 0, -100 })]
    [InlineData("speed=0.1..0.35:0.1", new[] { 0.1, 0.2, 0.3 })]
    public void Parse_Range_FromAndToIncludedEachValueFromTheStart(string text, double[] expected)
    {
        var axis = SweepAxis.Parse(text, "--rows");

        Assert.Equal(expected.Length, axis.Values.Count);
        for (var i = 0; i < expected.Length; i++)
        {
            Assert.Equal(expected[i], axis.Values[i], 12);
        }
    }

    private static readonly MachineProfile ThreeAxis = MachineProfile.Default with { Z = new ZAxisProfile { FocusMm = 12.5, MinMm = 5, MaxMm = 20 } };

    [Fact]
    public void Build_FocusRows_EachCellItsAbsoluteZFromTheVisibleFocus()
    {
        var plan = SweepPlan.Build(Spec("focus=-100,0,100", "speed=1,2") with { Profile = ThreeAxis });

        Assert.Equal(6, plan.Cells.Count);
        foreach (var cell in plan.Cells)
        {
            Assert.Equal(ThreeAxis.Z!.MicrostepsAt(cell.Parameters["focusUm"]), cell.FocusZMicrosteps);
        }

        // 12.4 mm / 0.09921875 µm = 124976.38 -> 124976; 12.6 mm = 126992.13 -> 126992.
        Assert.Equal([124976L, 124976, 125984, 125984, 126992, 126992], plan.Cells.Select(c => c.FocusZMicrosteps!.Value));
        Assert.Null(SweepPlan.Build(Spec("speed=1,2") with { Profile = ThreeAxis }).Cells[0].FocusZMicrosteps);
    }

    [Fact]
    public void EstimatedSeconds_FocusRows_AddTheZMovesToTheSameCellsWithoutThem()
    {
        var focus = SweepPlan.Build(Spec("focus=-50,0,50") with { Profile = ThreeAxis });
        var still = SweepPlan.Build(Spec("passes=1,1,1") with { Profile = ThreeAxis });

        // Four moves of 504 microsteps (50 µm): to -50, 0, +50 and back to 0. At 1 mm/s (data 1075 = 10078.1 microsteps/s)
        // and 50 mm/s² (data 45 = 506250 microsteps/s²) each is 504 / 10078.1 + 10078.1 / 506250 = 0.0699 s of motion,
        // plus the laser's switch-off and the move's command and reply (tens of ms at 9600 baud), and before the first Z's
        // identification and settings (10 round trips of two 6-byte frames, 12.5 ms at 9600 baud, and the adapter's 2 x 1 ms).
        var moves = focus.EstimatedSeconds - still.EstimatedSeconds;
        Assert.Equal(moves, focus.FocusMovesSeconds(), 9);
        Assert.InRange(moves - (10 * 0.0145), 4 * 0.0699, 4 * (0.0699 + 0.05));
        Assert.Equal(0, still.FocusMovesSeconds());
    }

    [Theory]
    [InlineData("focus=0", null, "--rows focus=0: focus 0 µm: the machine has no Z axis: add a \"z\" section to the machine profile")]
    [InlineData("speed=1", "focus=-50,50", "--columns focus=-50,50: focus -50 µm: the machine has no Z axis")]
    public void Build_FocusWithoutZAxis_Refused(string rows, string? columns, string expected)
    {
        var ex = Assert.Throws<SweepException>(() => SweepPlan.Build(Spec(rows, columns)));

        Assert.Equal(expected, ex.Message[..Math.Min(expected.Length, ex.Message.Length)]);
    }

    [Fact]
    public void Build_FocusOutsideTheZLimits_RefusedBeforeAnythingIsPlanned()
    {
        var ex = Assert.Throws<SweepException>(() => SweepPlan.Build(Spec("focus=0,8000") with { Profile = ThreeAxis }));

        Assert.Equal("--rows focus=0,8000: focus 8000 µm: puts Z at 20.5 mm, outside z.minMm..z.maxMm 5..20 mm (the visible focus z.focusMm is 12.5 mm)", ex.Message);
    }

    [Fact]
    public void Build_ImagePattern_EveryCellTheImageItsLargerSideTheCell()
    {
        var image = new BitMask(4, 2);
        image[0, 0] = image[3, 1] = true;

        var plan = SweepPlan.Build(Spec("speed=1,2") with { Pattern = SweepPattern.Image, CellImage = image, CellImageName = "mark.png" });

        // 1 mm over 4 pixels: 250 µm a pixel, the image 1 x 0.5 mm to within a microstep (0.0992 µm).
        var job = plan.Cells[1].Job;
        Assert.Same(image, job.Mask);
        Assert.Equal(250, job.Geometry.PitchUm, 9);
        Assert.InRange(job.Geometry.AchievedWidthMm, 1 - 0.0001, 1 + 0.0001);
        Assert.InRange(job.Geometry.AchievedHeightMm, 0.5 - 0.0001, 0.5 + 0.0001);
    }

    [Theory]
    [InlineData(null, "speed=1", "--pattern image needs the cell's image")]
    [InlineData(4, "pitch=50,100", "so its pitch cannot be swept")]
    [InlineData(20000, "speed=1", "a pixel of 0.05: must be")]
    public void Build_ImagePatternBad_Refused(int? side, string rows, string fragment)
    {
        var spec = Spec(rows) with { Pattern = SweepPattern.Image, CellImage = side is { } n ? new BitMask(n, 1) : null, CellImageName = "mark.png" };

        var ex = Assert.Throws<SweepException>(() => SweepPlan.Build(spec));

        Assert.Contains(fragment, ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void MaskSha256_SameBitsSameHashOtherBitsOther()
    {
        var a = SweepPlan.CellMask(SweepPattern.Lines, 10);
        var b = SweepPlan.CellMask(SweepPattern.Lines, 10);
        var c = SweepPlan.CellMask(SweepPattern.Dots, 10);

        Assert.Equal(SweepPlan.MaskSha256(a), SweepPlan.MaskSha256(b));
        Assert.NotEqual(SweepPlan.MaskSha256(a), SweepPlan.MaskSha256(c));
        Assert.Equal(64, SweepPlan.MaskSha256(a).Length);
    }
}
