using System.Buffers.Binary;
using System.Diagnostics;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Motion;

namespace LaserEngrave.Simulator.Tests.Burn;

/// <summary>
/// The pulse figures on hand-made trajectories. The grid has whole-microstep edges (pixel c spans x in
/// [1000 + 500 c, 1500 + 500 c)), the stage burns at 10,000 microsteps/s and the laser fires at 1 kHz, so pulses are
/// D = 10 microsteps apart and every expected position below is worked out by hand from those numbers.
/// </summary>
public class BurnRecorderPulseTests
{
    private const double MicrostepUm = 0.09921875;
    private const double Speed = 10_000;   // microsteps/s
    private const double Hz = 1000;
    private const double Spacing = Speed / Hz; // D, microsteps
    private const double BurnSpeedMmPerS = Speed * MicrostepUm / 1000;

    private static readonly BurnGrid Grid = new(1000, 2000, 500, 10, 3);

    // Row 1, columns 2 and 3: x from 2000 to 3000.
    private static readonly BitMask Run = Mask((1, [2, 3]));

    [Fact]
    public void Analyze_PerfectlyTimedRun_HasNoEdgeErrorAndNoDwell()
    {
        var recorder = PerfectRun(Speed, out var expected);

        var report = recorder.Analyze(Grid, expected, BurnSpeedMmPerS);

        Assert.Equal(100, report.Pulses);
        Assert.Equal(new EdgeFigures(2, 0, 0, 0), Rounded(report.Edges));
        Assert.Equal(new DwellFigures(0, 0), report.Dwells);
        Assert.Equal(0, report.LaserOnTravelCount);
        Assert.True(report.Burned.ContentEquals(expected));
    }

    [Fact]
    public void Analyze_SteadyRun_PulsesPerPixelArePitchOverSpacing()
    {
        var recorder = PerfectRun(2 * Speed, out var expected);

        var report = recorder.Analyze(Grid, expected, 2 * BurnSpeedMmPerS);

        // 500 microsteps a pixel, a pulse every 20.
        Assert.Equal(new PulsesPerPixelFigures(25, 25, 25), report.PulsesPerPixel);
        Assert.Equal(new EdgeFigures(2, 0, 0, 0), Rounded(report.Edges));
    }

    [Fact]
    public void Analyze_LaserOnFiveMillisecondsBeforeTheMove_DwellsFivePulsesAndMissesTheStartEdgeByHalfASpacing()
    {
        var (x, _, recorder) = Machine(2000, Grid.RowLine(1));
        recorder.RecordLaser(1.0, Hz);
        MoveAt(x, 1.005, 2000, 3000, Speed);
        recorder.RecordLaser(1.1, 0);

        var report = recorder.Analyze(Grid, Run, BurnSpeedMmPerS);

        // Five pulses at 2000 while standing (1.000 to 1.004 s), then one every 10 microsteps from 2000 at 1.005 s to
        // 2940 at 1.099 s. Start: 2000 against 2000 + D/2. End: 2940 against 3000 - D/2.
        var start = Spacing / 2 * MicrostepUm;
        var end = Math.Abs(2940 - (3000 - (Spacing / 2))) * MicrostepUm;
        Assert.Equal(new DwellFigures(1, 5), report.Dwells);
        Assert.Equal(new EdgeFigures(2, Round((start + end) / 2), Round(end), 0), Rounded(report.Edges));
        Assert.Equal(5 + 95, report.Pulses);
    }

    [Fact]
    public void Analyze_LaserOnBeforeTheMove_ShowsTheOverburnInTheDoseMap()
    {
        var (x, _, recorder) = Machine(2000, Grid.RowLine(1));
        recorder.RecordLaser(1.0, Hz);
        MoveAt(x, 1.005, 2000, 3000, Speed);
        recorder.RecordLaser(1.1, 0);

        var dose = recorder.Analyze(Grid, Run, BurnSpeedMmPerS).Dose;

        // Column 2's first sub-cell spans x 2000..2125: the 5 standing pulses and 13 moving ones (2000 to 2120); the
        // next spans 2125..2250: 12 (2130 to 2240). Row 1's line (2750) is in its third sub-row (2750..2875).
        Assert.Equal(18, dose[2 * 4, (1 * 4) + 2]);
        Assert.Equal(12, dose[(2 * 4) + 1, (1 * 4) + 2]);
        Assert.Equal(18, dose.Max);
        Assert.Equal(5 + 50, dose.PulsesOnPixel(2, 1));
    }

    [Fact]
    public void WriteDosePng_TheMostPulsesAreBlackNoneWhite()
    {
        var (x, _, recorder) = Machine(2000, Grid.RowLine(1));
        recorder.RecordLaser(1.0, Hz);
        MoveAt(x, 1.005, 2000, 3000, Speed);
        recorder.RecordLaser(1.1, 0);
        using var png = new MemoryStream();

        recorder.Analyze(Grid, Run).WriteDosePng(png);
        png.Position = 0;
        var image = ImageLoader.Load(png, "dose.png");

        // 18 pulses (the most), 12 of 18 (255 - 255 x 12 / 18 = 85), none.
        Assert.Equal(Rgba32.Black, image.GetPixel(2 * 4, (1 * 4) + 2));
        Assert.Equal(new Rgba32(85, 85, 85), image.GetPixel((2 * 4) + 1, (1 * 4) + 2));
        Assert.Equal(Rgba32.White, image.GetPixel(0, 0));
    }

    [Fact]
    public void Analyze_PerfectlyTimedReverseRun_HasNoEdgeError()
    {
        var (x, _, recorder) = Machine(5000, Grid.RowLine(1));
        MoveAt(x, 0, 5000, 1000, Speed);

        // At 3000 - D/2 = 2995 after 2005 microsteps; 100 pulses, the last at 2005 = 2000 + D/2.
        recorder.RecordLaser(0.2005, Hz);
        recorder.RecordLaser(0.3005, 0);

        var report = recorder.Analyze(Grid, Run, BurnSpeedMmPerS);

        Assert.Equal(100, report.Pulses);
        Assert.Equal(new EdgeFigures(2, 0, 0, 0), Rounded(report.Edges));
        Assert.Equal(new DwellFigures(0, 0), report.Dwells);
        Assert.True(report.Burned.ContentEquals(Run));
    }

    [Fact]
    public void Analyze_ReverseRunWithTheLaserOnBeforeTheMove_MissesItsRightEdge()
    {
        var (x, _, recorder) = Machine(3000, Grid.RowLine(1));
        recorder.RecordLaser(1.0, Hz);
        MoveAt(x, 1.005, 3000, 2000, Speed);
        recorder.RecordLaser(1.1, 0);

        var report = recorder.Analyze(Grid, Run, BurnSpeedMmPerS);

        // Five pulses standing at 3000 (on column 5's right edge), then from 3000 down to 2060 at 1.099 s.
        var right = Spacing / 2 * MicrostepUm;
        var left = (2060 - (2000 + (Spacing / 2))) * MicrostepUm;
        Assert.Equal(new DwellFigures(1, 5), report.Dwells);
        Assert.Equal(new EdgeFigures(2, Round((left + right) / 2), Round(left), 0), Rounded(report.Edges));
        Assert.Equal(0, report.LaserOnTravelCount);
    }

    [Fact]
    public void Analyze_PulsesOnAWhitePixel_AreLaserOnTravelAndTheRunIsMissing()
    {
        var (_, _, recorder) = Machine(4750, Grid.RowLine(0));
        recorder.RecordLaser(0, Hz);
        recorder.RecordLaser(0.003, 0);

        var report = recorder.Analyze(Grid, Run, BurnSpeedMmPerS);

        Assert.Equal(3, report.LaserOnTravelCount);
        Assert.Equal(0, report.LaserOnTravelUm);
        Assert.Equal(1, report.ExtraPixels);
        Assert.Equal(2, report.MissingPixels);
        Assert.Equal(new EdgeFigures(0, 0, 0, 1), report.Edges);
        Assert.Equal(new PulsesPerPixelFigures(0, 0, 0), report.PulsesPerPixel);
    }

    [Theory]
    [InlineData(3000.5, 0)]
    [InlineData(1999.5, 0)]
    [InlineData(3001, 1)]
    [InlineData(1999, 1)]
    public void Analyze_PulseNearABlackPixelsEdge_IsTravelOnlyBeyondHalfAMicrostep(double at, int travel)
    {
        var (_, _, recorder) = Machine(at, Grid.RowLine(1));
        recorder.RecordLaser(0, Hz);
        recorder.RecordLaser(0.0005, 0);

        var report = recorder.Analyze(Grid, Run);

        Assert.Equal(travel, report.LaserOnTravelCount);
        Assert.Equal(travel, report.ExtraPixels);
    }

    [Fact]
    public void Analyze_PulsesInTheGapBetweenTwoRuns_CountForTheNearerRun()
    {
        // Runs at columns 2-3 (2000..3000) and 6-7 (4000..5000) of row 1: the gap splits at 3500. One pass at 10
        // microsteps a pulse: the first run's laser stays on to 3395, the second's comes on at 3605, both 400 microsteps
        // beyond their runs; the other two ends are exact (2005 and 4995).
        var (x, _, recorder) = Machine(1000, Grid.RowLine(1));
        MoveAt(x, 0, 1000, 6000, Speed);
        recorder.RecordLaser(0.1005, Hz);
        recorder.RecordLaser(0.2405, 0);
        recorder.RecordLaser(0.2605, Hz);
        recorder.RecordLaser(0.4005, 0);

        var report = recorder.Analyze(Grid, Mask((1, [2, 3, 6, 7])), BurnSpeedMmPerS);

        var off = 400 * MicrostepUm;
        Assert.Equal(new EdgeFigures(4, Round(2 * off / 4), Round(off), 0), Rounded(report.Edges));

        // On white columns 4 and 5: 3005 to 3395 and 3605 to 3995, 40 pulses each.
        Assert.Equal(80, report.LaserOnTravelCount);
    }

    [Theory]
    [InlineData(600, 1)]
    [InlineData(400, 0)]
    public void Analyze_PulsesLeftOfTheGrid_CountForTheBorderRunUpToAPixelBeyond(double at, int caught)
    {
        // Run: columns 0 and 1 of row 1 (1000..2000); the grid's border is at 1000, one pixel beyond it at 500.
        var (_, _, recorder) = Machine(at, Grid.RowLine(1));
        recorder.RecordLaser(0, Hz);
        recorder.RecordLaser(0.003, 0);

        var edges = recorder.Analyze(Grid, Mask((1, [0, 1])), BurnSpeedMmPerS).Edges!;

        var left = (1000 + (Spacing / 2) - at) * MicrostepUm;
        var right = (2000 - (Spacing / 2) - at) * MicrostepUm;
        var expected = caught == 1 ? new EdgeFigures(2, Round((left + right) / 2), Round(right), 0) : new EdgeFigures(0, 0, 0, 1);
        Assert.Equal(expected, Rounded(edges));
    }

    [Fact]
    public void Analyze_CrawlUnderATenthOfTheBurnSpeed_IsDwell()
    {
        var (x, _, recorder) = Machine(2000, Grid.RowLine(1));
        MoveAt(x, 0, 2000, 2100, Speed / 20);
        recorder.RecordLaser(0, Hz);
        recorder.RecordLaser(0.005, 0);
        MoveAt(x, 1, 2100, 2300, Speed / 5);
        recorder.RecordLaser(1, Hz);
        recorder.RecordLaser(1.005, 0);

        var report = recorder.Analyze(Grid, Run, BurnSpeedMmPerS);

        // At a twentieth of the burn speed all 5 pulses dwell; at a fifth none does.
        Assert.Equal(new DwellFigures(1, 5), report.Dwells);
    }

    [Fact]
    public void Analyze_TwoStandsSeparatedBySwitchingOff_AreTwoDwells()
    {
        var (_, _, recorder) = Machine(2500, Grid.RowLine(1));
        recorder.RecordLaser(0, Hz);
        recorder.RecordLaser(0.003, 0);
        recorder.RecordLaser(0.010, Hz);
        recorder.RecordLaser(0.012, 0);

        Assert.Equal(new DwellFigures(2, 5), recorder.Analyze(Grid, Run, BurnSpeedMmPerS).Dwells);
    }

    [Fact]
    public void Analyze_WithoutABurnSpeed_HasNoEdgesOrDwells()
    {
        var recorder = PerfectRun(Speed, out var expected);

        var report = recorder.Analyze(Grid, expected);

        Assert.Null(report.Edges);
        Assert.Null(report.Dwells);
        Assert.Equal(100, report.Pulses);
    }

    [Fact]
    public void Analyze_LaserOnForFiveMilliseconds_FiresFivePulses()
    {
        var (_, _, recorder) = Machine(2500, Grid.RowLine(1));
        recorder.RecordLaser(2.0, Hz);
        recorder.RecordLaser(2.005, 0);

        // At 2.000, 2.001, 2.002, 2.003 and 2.004 s; none at the switch-off instant.
        Assert.Equal(5, recorder.Analyze(Grid).Pulses);
    }

    [Fact]
    public void Restart_WhileTheLaserIsOn_KeepsThePulsesInStep()
    {
        var (_, _, recorder) = Machine(2500, Grid.RowLine(1));
        recorder.RecordLaser(0, Hz);
        recorder.Restart(0.0105);
        recorder.RecordLaser(0.02, 0);

        // 0.011 to 0.019 s: the train is timed from the switch-on, not from the restart.
        Assert.Equal(9, recorder.Analyze(Grid).Pulses);
    }

    [Fact]
    public void WriteDosePng_WritesAGreyPngOfFourByFourSubcellsAPixel()
    {
        var recorder = PerfectRun(Speed, out var expected);
        using var png = new MemoryStream();

        recorder.Analyze(Grid, expected).WriteDosePng(png);

        var bytes = png.ToArray();
        Assert.Equal([0x89, (byte)'P', (byte)'N', (byte)'G'], bytes[..4]);
        Assert.Equal(Grid.WidthPx * 4, BinaryPrimitives.ReadInt32BigEndian(bytes.AsSpan(16)));
        Assert.Equal(Grid.HeightPx * 4, BinaryPrimitives.ReadInt32BigEndian(bytes.AsSpan(20)));
        Assert.Equal(8, bytes[24]);
        Assert.Equal(0, bytes[25]);
    }

    [Fact]
    public void Analyze_MillionPulses_AddsUpInOnePass()
    {
        // 200 rows of 200 px, black in runs of 5 every 10: each run burned on the fly at full speed, 50 pulses a
        // pixel, 100 black pixels a row, 1,000,000 pulses in all. Run by hand to read the time in the test output.
        const int side = 200;
        var grid = new BurnGrid(1000, 2000, 500, side, side);
        var expected = new BitMask(side, side);
        var (x, y, recorder) = Machine(0, grid.RowLine(0));
        var t = 0.0;
        for (var row = 0; row < side; row++)
        {
            var forward = row % 2 == 0;
            double from = forward ? 0 : 102_000, to = forward ? 102_000 : 0;
            MoveAt(y, t, y.PositionAt(t), grid.RowLine(row), 1_000_000);
            t += 0.001;
            MoveAt(x, t, from, to, Speed);
            for (var column = 0; column < side; column += 10)
            {
                for (var c = column; c < column + 5; c++)
                {
                    expected[c, row] = true;
                }

                // Switched on at the run's near edge + D/2, off one run length later.
                var near = forward ? grid.ColumnEdge(column) + (Spacing / 2) : grid.ColumnEdge(column + 5) - (Spacing / 2);
                var on = t + (Math.Abs(near - from) / Speed);
                recorder.RecordLaser(on, Hz);
                recorder.RecordLaser(on + (5 * 500 / Speed), 0);
            }

            t += 102_000 / Speed;
        }

        using var process = Process.GetCurrentProcess();
        var cpu = process.TotalProcessorTime;
        var clock = Stopwatch.StartNew();
        var report = recorder.Analyze(grid, expected, BurnSpeedMmPerS);
        clock.Stop();
        process.Refresh();
        TestContext.Current.TestOutputHelper?.WriteLine(
            $"Analyze: {report.Pulses:N0} pulses in {clock.Elapsed.TotalMilliseconds:0} ms of wall time, {(process.TotalProcessorTime - cpu).TotalMilliseconds:0} ms of CPU");

        Assert.Equal(1_000_000, report.Pulses);
        Assert.Equal(new EdgeFigures(2 * 20 * side, 0, 0, 0), Rounded(report.Edges));
        Assert.Equal(new PulsesPerPixelFigures(50, 50, 50), report.PulsesPerPixel);
        Assert.Equal(new DwellFigures(0, 0), report.Dwells);
        Assert.Equal(0, report.LaserOnTravelCount);
        Assert.True(report.Burned.ContentEquals(expected));
    }

    [Fact]
    public void Analyze_StopGoRunsAtOneKilohertzAndOneMmPerS_BurnExactlyTheImage()
    {
        // 55 µm pixels, 1 mm/s, 50 mm/s² ramps, as today's executor: the laser switched on 20 ms before each run's move
        // (standing on its first edge) and off 10 ms after it stops (on its last edge); the travel between runs dark.
        const double pitch = 55 / MicrostepUm, speed = 1000 / MicrostepUm, acceleration = 50_000 / MicrostepUm;
        var image = new BitMask(8, 3);
        string[] rows = ["..##..#.", "#......#", ".######."];
        var grid = new BurnGrid(20_000.4, 30_000.6, pitch, 8, 3);
        var (x, y, recorder) = Machine(0, grid.RowLine(0));
        var t = 0.0;
        var runs = 0;
        for (var row = 0; row < rows.Length; row++)
        {
            MoveAt(y, t, y.PositionAt(t), grid.RowLine(row), speed);
            t = y.EndSeconds + 0.01;
            for (var column = 0; column < rows[row].Length; column++)
            {
                if (rows[row][column] != '#' || (column > 0 && rows[row][column - 1] == '#'))
                {
                    continue;
                }

                var end = column;
                while (end + 1 < rows[row].Length && rows[row][end + 1] == '#')
                {
                    end++;
                }

                for (var c = column; c <= end; c++)
                {
                    image[c, row] = true;
                }

                MoveAt(x, t, x.PositionAt(t), grid.ColumnEdge(column), 4 * speed);
                t = x.EndSeconds + 0.01;
                recorder.RecordLaser(t, Hz);
                Trapezoid(x, t + 0.02, grid.ColumnEdge(column), grid.ColumnEdge(end + 1), speed, acceleration);
                t = x.EndSeconds + 0.01;
                recorder.RecordLaser(t, 0);
                runs++;
            }
        }

        var report = recorder.Analyze(grid, image, 1);

        Assert.True(report.Burned.ContentEquals(image), $"{report.ExtraPixels} extra, {report.MissingPixels} missing");
        Assert.Equal(0, report.LaserOnTravelCount);
        Assert.Equal(2 * runs, report.Dwells!.Count);
        Assert.Equal(2 * runs, report.Edges!.Count);
    }

    // A run over columns 2 and 3 of row 1 at `speed`, switched on at 2000 + D/2 and off after 1000 microsteps of travel.
    private static BurnRecorder PerfectRun(double speed, out BitMask expected)
    {
        var (x, _, recorder) = Machine(1000, Grid.RowLine(1));
        MoveAt(x, 0, 1000, 5000, speed);
        var spacing = speed / Hz;
        var on = (1000 + (spacing / 2)) / speed;
        recorder.RecordLaser(on, Hz);
        recorder.RecordLaser(on + (1000 / speed), 0);
        expected = Run;
        return recorder;
    }

    private static double Round(double um) => Math.Round(um, 6);

    private static EdgeFigures? Rounded(EdgeFigures? edges) =>
        edges is null ? null : edges with { MeanErrorUm = Round(edges.MeanErrorUm), MaxErrorUm = Round(edges.MaxErrorUm) };

    private static (AxisTrajectory X, AxisTrajectory Y, BurnRecorder Recorder) Machine(double x0, double y0)
    {
        var x = new AxisTrajectory(x0);
        var y = new AxisTrajectory(y0);
        return (x, y, new BurnRecorder(x, y, MicrostepUm, MicrostepUm));
    }

    // A constant-speed move (no ramps), enough to place the pulses by hand.
    private static void MoveAt(AxisTrajectory axis, double start, double from, double to, double speed)
    {
        var duration = Math.Abs(to - from) / speed;
        axis.Replace(start, [new MotionSegment(start, from, Math.Sign(to - from) * speed, 0, duration), MotionSegment.Hold(start + duration, to)]);
    }

    // A trapezoidal move from rest to rest: ramps at `acceleration`, cruising at `speed` (the distance allows it).
    private static void Trapezoid(AxisTrajectory axis, double start, double from, double to, double speed, double acceleration)
    {
        var sign = Math.Sign(to - from);
        var ramp = speed / acceleration;
        var cruise = (Math.Abs(to - from) - (speed * ramp)) / speed;
        var cruiseFrom = from + (sign * speed * ramp / 2);
        var decelerateFrom = cruiseFrom + (sign * speed * cruise);
        axis.Replace(start, [
            new MotionSegment(start, from, 0, sign * acceleration, ramp),
            new MotionSegment(start + ramp, cruiseFrom, sign * speed, 0, cruise),
            new MotionSegment(start + ramp + cruise, decelerateFrom, sign * speed, -sign * acceleration, ramp),
            MotionSegment.Hold(start + ramp + cruise + ramp, to)]);
    }

    private static BitMask Mask(params (int Row, int[] Columns)[] set)
    {
        var mask = new BitMask(Grid.WidthPx, Grid.HeightPx);
        foreach (var (row, columns) in set)
        {
            foreach (var column in columns)
            {
                mask[column, row] = true;
            }
        }

        return mask;
    }
}
