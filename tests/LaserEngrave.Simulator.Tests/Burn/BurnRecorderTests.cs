using LaserEngrave.Core.Imaging;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Motion;

namespace LaserEngrave.Simulator.Tests.Burn;

/// <summary>The burn recorder on hand-made trajectories: constant-speed moves with the laser switched on and off by hand.</summary>
/// <remarks>At 1 kHz one pulse lands every millisecond from the instant the laser switched on (BurnRecorderPulseTests for the pulse figures).</remarks>
public class BurnRecorderTests
{
    private const double MicrostepUm = 0.09921875;

    // 10 x 3 px, origin and pitch not whole microsteps, as a real job's are (10 mm / 180 px).
    private static readonly BurnGrid Grid = new(1000.3, 2000.7, 559.93, 10, 3);

    [Fact]
    public void Analyze_BurnRunOnARowLine_BurnsExactlyItsPixels()
    {
        var (x, y, recorder) = Machine(Grid.ColumnEdge(0), Grid.RowLine(1));
        MoveAt(x, 1.0, Grid.ColumnEdge(0), Grid.ColumnEdge(2), 5000);
        recorder.RecordLaser(2.0, 1000);
        MoveAt(x, 2.01, Grid.ColumnEdge(2), Grid.ColumnEdge(6), 1000);
        recorder.RecordLaser(2.01 + (Grid.ColumnEdge(6) - Grid.ColumnEdge(2)) / 1000.0 + 0.01, 0);
        var expected = Mask(Grid, (1, [2, 3, 4, 5]));

        // The 10 ms stand on the run's right edge lands on column 6's left edge: the expected image says that is column 5's.
        var report = recorder.Analyze(Grid, expected);

        Assert.Equal(expected, report.Burned, MaskComparer.Instance);
        Assert.Equal(0, report.LaserOnTravelUm);
        Assert.Equal(0, report.DwellCount);
        Assert.Equal(0.01, report.LongestDwellSeconds, 9);
    }

    [Fact]
    public void Analyze_LaserOnWhileYMovesOverWhite_EveryPulseIsTravel()
    {
        var (_, y, recorder) = Machine(Grid.ColumnEdge(0), Grid.RowLine(0));
        recorder.RecordLaser(0.5, 1000);
        MoveAt(y, 1.0, Grid.RowLine(0), Grid.RowLine(2), 2000);
        recorder.RecordLaser(10, 0);

        var report = recorder.Analyze(Grid, new BitMask(Grid.WidthPx, Grid.HeightPx));

        // 9.5 s at 1 kHz, every pulse on column 0 of the row the stage is over.
        Assert.Equal(9500, report.LaserOnTravelCount);
        Assert.Equal((Grid.RowLine(2) - Grid.RowLine(0)) * MicrostepUm, report.LaserOnTravelUm, 6);
        Assert.Equal(Mask(Grid, (0, [0]), (1, [0]), (2, [0])), report.Burned, MaskComparer.Instance);
        Assert.Equal(3, report.ExtraPixels);
    }

    [Fact]
    public void Analyze_OnePulseOnAPixel_BurnsIt()
    {
        var (_, _, recorder) = Machine((Grid.ColumnEdge(4) + Grid.ColumnEdge(5)) / 2, Grid.RowLine(2));
        recorder.RecordLaser(0, 1000);
        recorder.RecordLaser(0.0005, 0);

        var report = recorder.Analyze(Grid);

        Assert.Equal(1, report.Pulses);
        Assert.Equal(Mask(Grid, (2, [4])), report.Burned, MaskComparer.Instance);
    }

    [Fact]
    public void Analyze_PulsesFurtherApartThanAPixel_LeaveThePixelsBetweenWhite()
    {
        var (x, _, recorder) = Machine(Grid.ColumnEdge(0), Grid.RowLine(0));
        MoveAt(x, 0, Grid.ColumnEdge(0), Grid.ColumnEdge(10), 1_000_000);
        recorder.RecordLaser(0, 1000);
        recorder.RecordLaser(0.0045, 0);

        // A pulse every 1000 microsteps from 1000: at 1000, 2000, 3000, 4000 and 5000, in columns 0, 1, 3, 5 and 7.
        var report = recorder.Analyze(Grid);

        Assert.Equal(Mask(Grid, (0, [0, 1, 3, 5, 7])), report.Burned, MaskComparer.Instance);
    }

    [Fact]
    public void Analyze_RunCrossingAWhitePixel_CountsTravelOverWhite()
    {
        var expected = Mask(Grid, (0, [1, 2, 4]));
        var (x, _, recorder) = Machine(Grid.ColumnEdge(1), Grid.RowLine(0));
        recorder.RecordLaser(0, 1000);
        MoveAt(x, 0.01, Grid.ColumnEdge(1), Grid.ColumnEdge(5), 2000);
        recorder.RecordLaser(5, 0);

        var report = recorder.Analyze(Grid, expected);

        // Pulses 2 microsteps apart from column 1's edge; those more than half a microstep inside white column 3 are travel.
        var travel = 0;
        for (var at = Grid.ColumnEdge(1); at <= Grid.ColumnEdge(5); at += 2)
        {
            travel += at > Grid.ColumnEdge(3) + 0.5 && at < Grid.ColumnEdge(4) - 0.5 ? 1 : 0;
        }

        Assert.Equal(travel, report.LaserOnTravelCount);
        Assert.Equal(travel * 2 * MicrostepUm, report.LaserOnTravelUm, 6);
        Assert.Equal(1, report.ExtraPixels);
        Assert.Equal(0, report.MissingPixels);
    }

    [Fact]
    public void Analyze_BurnRunMatchingTheImage_HasNoTravel()
    {
        var expected = Mask(Grid, (0, [1, 2, 3]));
        var (x, _, recorder) = Machine(Grid.ColumnEdge(1), Grid.RowLine(0));
        recorder.RecordLaser(0, 1000);
        MoveAt(x, 0.01, Grid.ColumnEdge(1), Grid.ColumnEdge(4), 2000);
        recorder.RecordLaser(5, 0);

        var report = recorder.Analyze(Grid, expected);

        Assert.Equal(0, report.LaserOnTravelUm);
        Assert.Equal(0, report.LaserOnTravelCount);
        Assert.Equal(0, report.ExtraPixels + report.MissingPixels);
    }

    [Fact]
    public void Analyze_XMoveOffTheRowLineWithinItsCell_BurnsThatRow()
    {
        var expected = Mask(Grid, (0, [0, 1]));
        var (x, _, recorder) = Machine(Grid.ColumnEdge(0), Grid.RowLine(0) + 3);
        recorder.RecordLaser(0, 1000);
        MoveAt(x, 0, Grid.ColumnEdge(0), Grid.ColumnEdge(2), 1000);
        recorder.RecordLaser(5, 0);

        var report = recorder.Analyze(Grid, expected);

        Assert.Equal(expected, report.Burned, MaskComparer.Instance);
        Assert.Equal(0, report.LaserOnTravelCount);
    }

    [Fact]
    public void Analyze_XMoveAboveTheGrid_EveryPulseIsTravel()
    {
        var (x, _, recorder) = Machine(Grid.ColumnEdge(0), Grid.RowEdge(0) - 1);
        recorder.RecordLaser(0, 1000);
        MoveAt(x, 0, Grid.ColumnEdge(0), Grid.ColumnEdge(2), 1000);
        recorder.RecordLaser(5, 0);

        var report = recorder.Analyze(Grid);

        Assert.Equal(0, report.Burned.CountSet());
        Assert.Equal(5000, report.LaserOnTravelCount);
        Assert.Equal((Grid.ColumnEdge(2) - Grid.ColumnEdge(0)) * MicrostepUm, report.LaserOnTravelUm, 6);
    }

    [Fact]
    public void Analyze_XMovePastTheGridEdge_ThePartOutsideIsTravel()
    {
        var (x, _, recorder) = Machine(Grid.ColumnEdge(8), Grid.RowLine(1));
        recorder.RecordLaser(0, 1000);
        MoveAt(x, 0, Grid.ColumnEdge(8), Grid.ColumnEdge(10) + 500, 1000);
        recorder.RecordLaser(5, 0);

        var report = recorder.Analyze(Grid);

        // Pulse k lands at column 8's edge + k (1 microstep a millisecond) until the stop: outside from the first one past
        // the grid's edge (the one on it lands on column 9) to the last before the switch-off at k = 5000.
        var firstOutside = Grid.ColumnEdge(10) + 1 - Grid.ColumnEdge(8);
        Assert.Equal(Mask(Grid, (1, [8, 9])), report.Burned, MaskComparer.Instance);
        Assert.Equal(5000 - firstOutside, report.LaserOnTravelCount);
        Assert.Equal(500 * MicrostepUm, report.LaserOnTravelUm, 6);
    }

    [Fact]
    public void Analyze_TwoLaserOnPeriodsOffTheGrid_CountEveryPulse()
    {
        var (_, y, recorder) = Machine(0, 0);
        recorder.RecordLaser(0, 1000);
        MoveAt(y, 0, 0, 100, 1000);
        recorder.RecordLaser(1, 0);
        recorder.RecordLaser(2, 1000);
        MoveAt(y, 2, 100, 200, 1000);
        recorder.RecordLaser(3, 0);

        Assert.Equal(2000, recorder.Analyze(Grid).LaserOnTravelCount);
    }

    [Fact]
    public void Analyze_StandingStillWithTheLaserOn_CountsDwellOverTheTolerance()
    {
        var (x, _, recorder) = Machine(Grid.ColumnEdge(0), Grid.RowLine(0));
        recorder.RecordLaser(1.0, 1000);
        recorder.RecordLaser(1.1, 0);
        recorder.RecordLaser(2.0, 1000);
        recorder.RecordLaser(2.02, 0);
        recorder.RecordLaser(3.0, 1000);
        MoveAt(x, 3.03, Grid.ColumnEdge(0), Grid.ColumnEdge(1), 1000);
        recorder.RecordLaser(5.0, 0);

        var report = recorder.Analyze(Grid);

        // 100 ms, 20 ms (under 25), 30 ms before the move and about 1.4 s after it.
        Assert.Equal(3, report.DwellCount);
        var after = 5.0 - (3.03 + ((Grid.ColumnEdge(1) - Grid.ColumnEdge(0)) / 1000.0));
        Assert.Equal(0.1 + 0.03 + after, report.DwellSeconds, 6);
        Assert.Equal(after, report.LongestDwellSeconds, 6);
        Assert.Equal(0.1 + 0.02 + 2.0, report.LaserOnSeconds, 9);
    }

    [Fact]
    public void Analyze_LaserStillOn_IntervalEndsAtNow()
    {
        var now = 4.0;
        var x = new AxisTrajectory(0);
        var y = new AxisTrajectory(0);
        var recorder = new BurnRecorder(x, y, MicrostepUm, MicrostepUm, now: () => now);
        recorder.RecordLaser(1.0, 1000);

        Assert.Equal(3.0, recorder.Analyze(Grid).LaserOnSeconds, 9);
    }

    [Fact]
    public void RefusedMoves_Recorded_AreCounted()
    {
        var (_, _, recorder) = Machine(0, 0);
        recorder.RecordRefusedMove(new RefusedMove(1, AxisName.X, 20, 20));
        recorder.RecordRefusedMove(new RefusedMove(2, AxisName.Y, 21, 21));

        Assert.Equal(2, recorder.Analyze(Grid).RefusedMoves);
    }

    [Fact]
    public void Restart_OnlyWhatFollowsCounts()
    {
        var (x, _, recorder) = Machine(Grid.ColumnEdge(0), Grid.RowLine(0));
        recorder.RecordLaser(0, 1000);
        MoveAt(x, 0, Grid.ColumnEdge(0), Grid.ColumnEdge(3), 1000);
        recorder.RecordLaser(3, 0);
        recorder.RecordRefusedMove(new RefusedMove(1, AxisName.X, 20, 20));

        recorder.Restart(4);
        recorder.RecordLaser(5, 1000);
        MoveAt(x, 5, Grid.ColumnEdge(3), Grid.ColumnEdge(4), 1000);
        recorder.RecordLaser(7, 0);

        var report = recorder.Analyze(Grid, Mask(Grid, (0, [3])));
        Assert.Equal(Mask(Grid, (0, [3])), report.Burned, MaskComparer.Instance);
        Assert.Equal(0, report.RefusedMoves);
    }

    [Fact]
    public void Analyze_ExpectedOfAnotherSize_Throws()
    {
        var (_, _, recorder) = Machine(0, 0);

        Assert.Throws<ArgumentException>(() => recorder.Analyze(Grid, new BitMask(3, 3)));
    }

    [Fact]
    public void WritePng_WritesAPngOfTheGridSize()
    {
        var (x, _, recorder) = Machine(Grid.ColumnEdge(0), Grid.RowLine(0));
        recorder.RecordLaser(0, 1000);
        MoveAt(x, 0, Grid.ColumnEdge(0), Grid.ColumnEdge(2), 1000);
        recorder.RecordLaser(5, 0);
        using var png = new MemoryStream();

        recorder.Analyze(Grid).WritePng(png);

        var bytes = png.ToArray();
        Assert.Equal([0x89, (byte)'P', (byte)'N', (byte)'G'], bytes[..4]);
        Assert.Equal(Grid.WidthPx, System.Buffers.Binary.BinaryPrimitives.ReadInt32BigEndian(bytes.AsSpan(16)));
        Assert.Equal(Grid.HeightPx, System.Buffers.Binary.BinaryPrimitives.ReadInt32BigEndian(bytes.AsSpan(20)));
    }

    private static (AxisTrajectory X, AxisTrajectory Y, BurnRecorder Recorder) Machine(double x0, double y0)
    {
        var x = new AxisTrajectory(x0);
        var y = new AxisTrajectory(y0);
        return (x, y, new BurnRecorder(x, y, MicrostepUm, MicrostepUm));
    }

    // A constant-speed move (no ramps), enough to place the laser by hand.
    private static void MoveAt(AxisTrajectory axis, double start, double from, double to, double speed)
    {
        var duration = Math.Abs(to - from) / speed;
        axis.Replace(start, [new MotionSegment(start, from, Math.Sign(to - from) * speed, 0, duration), MotionSegment.Hold(start + duration, to)]);
    }

    private static BitMask Mask(BurnGrid grid, params (int Row, int[] Columns)[] set)
    {
        var mask = new BitMask(grid.WidthPx, grid.HeightPx);
        foreach (var (row, columns) in set)
        {
            foreach (var column in columns)
            {
                mask[column, row] = true;
            }
        }

        return mask;
    }

    private sealed class MaskComparer : IEqualityComparer<BitMask>
    {
        public static readonly MaskComparer Instance = new();

        public bool Equals(BitMask? a, BitMask? b) => a is not null && b is not null && a.ContentEquals(b);

        public int GetHashCode(BitMask obj) => obj.Width;
    }
}
