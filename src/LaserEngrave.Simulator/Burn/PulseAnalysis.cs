using System.Runtime.CompilerServices;
using LaserEngrave.Core;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Simulator.Motion;

namespace LaserEngrave.Simulator.Burn;

/// <summary>One analysis of the recorder: the Q-switch's pulse train walked in time order over both axes' motion segments.</summary>
/// <remarks>
/// While the laser is on at f Hz it fires one pulse every 1 / f s, the first at the instant it switched on, none at the
/// instant it switched off. Each pulse lands at the stage's position at its instant. The walk keeps one cursor per axis
/// and cuts every laser-on period at each change of either axis' segment, so each pulse is placed in constant time and a
/// job of a million pulses is a single pass.
/// </remarks>
internal sealed class PulseAnalysis
{
    // Instants closer than this are one: a pulse due as a move starts is fired by the moving stage, none at switch-off.
    private const double TimeEpsilon = 1e-9;

    // A pulse centre this close to a black pixel's edge lands on that pixel (positions are whole microsteps at rest).
    private const double EdgeSnapMicrosteps = 0.5;

    private const double PositionEpsilon = 1e-6;

    private readonly BurnGrid _grid;
    private readonly BitMask? _expected;
    private readonly double _xUm;
    private readonly double _yUm;
    private readonly double _dwellToleranceSeconds;
    private readonly double? _burnSpeedUmPerS;
    private readonly EdgeMeter? _edges;
    private readonly int[] _dose;

    // The grid's rounded edges, looked up once: a pulse needs several.
    private readonly long[] _columnEdges;
    private readonly long[] _rowEdges;

    private double _stand;
    private bool _dwelling;
    private bool _hasPrevious;
    private double _previousX;
    private double _previousY;

    public PulseAnalysis(BurnGrid grid, BitMask? expected, double xMicrostepUm, double yMicrostepUm, double dwellToleranceSeconds, double? burnSpeedMmPerS)
    {
        _grid = grid;
        _expected = expected;
        _xUm = xMicrostepUm;
        _yUm = yMicrostepUm;
        _dwellToleranceSeconds = dwellToleranceSeconds;
        _burnSpeedUmPerS = burnSpeedMmPerS is { } speed ? Units.MmToUm(speed) : null;
        _edges = expected is not null && burnSpeedMmPerS is not null ? new EdgeMeter(grid, expected) : null;
        _dose = new int[checked((long)grid.WidthPx * grid.HeightPx * DoseMap.SubcellsPerPixel * DoseMap.SubcellsPerPixel)];
        _columnEdges = [.. Enumerable.Range(0, grid.WidthPx + 1).Select(grid.ColumnEdge)];
        _rowEdges = [.. Enumerable.Range(0, grid.HeightPx + 1).Select(grid.RowEdge)];
    }

    public long Pulses { get; private set; }

    public double LaserOnSeconds { get; private set; }

    public double TravelUm { get; private set; }

    public int TravelPulses { get; private set; }

    public int StandCount { get; private set; }

    public double StandSeconds { get; private set; }

    public double LongestStandSeconds { get; private set; }

    public int DwellCount { get; private set; }

    public long DwellPulses { get; private set; }

    /// <summary>Pulses fired while either axis moved (its velocity not zero).</summary>
    public long MovingPulses { get; private set; }

    /// <summary>Fires every period's pulses; <paramref name="periods"/> in time order, not overlapping.</summary>
    /// <remarks>
    /// The walk and what it calls per pulse run once per job, over up to millions of pulses: they are compiled optimised
    /// from the start when compiled at run time (<see cref="HotPath"/>), since tiered compilation would leave them
    /// unoptimised for most of a short process (a third of the CLI's run time on a 600,000-pulse job).
    /// </remarks>
    [MethodImpl(HotPath.Optimized)]
    public void Walk(IReadOnlyList<LaserPeriod> periods, MotionSegment[] xs, MotionSegment[] ys)
    {
        int xi = 0, yi = 0;
        foreach (var period in periods)
        {
            LaserOnSeconds += period.ToSeconds - period.FromSeconds;
            var hz = period.FrequencyHz;
            var k = Math.Max(0L, (long)Math.Ceiling(((period.FromSeconds - period.OnSeconds) * hz) - 1e-6));
            var due = period.OnSeconds + (k / hz);
            for (var t = period.FromSeconds; t < period.ToSeconds;)
            {
                xi = Advance(xs, xi, t);
                yi = Advance(ys, yi, t);
                var x = xs[xi];
                var y = ys[yi];
                var end = Math.Min(period.ToSeconds, Math.Min(NextChange(xs, xi, t), NextChange(ys, yi, t)));
                Stand(end - t, x.PositionAt(t), x.PositionAt(end), y.PositionAt(t), y.PositionAt(end));
                for (; due < end - TimeEpsilon; due = period.OnSeconds + (++k / hz))
                {
                    Pulse(x, y, due, hz);
                }

                t = end;
            }

            EndStand();
            _dwelling = false;
            _hasPrevious = false;
        }
    }

    [MethodImpl(HotPath.Optimized)]
    public BurnReport Report(int refusedMoves)
    {
        var dose = new DoseMap(_grid.WidthPx, _grid.HeightPx, _dose);
        var burned = new BitMask(_grid.WidthPx, _grid.HeightPx);
        long extra = 0, missing = 0, counted = 0, sum = 0;
        int min = int.MaxValue, max = 0;
        for (var row = 0; row < _grid.HeightPx; row++)
        {
            for (var column = 0; column < _grid.WidthPx; column++)
            {
                var pulses = dose.PulsesOnPixel(column, row);
                var hit = pulses > 0;
                burned[column, row] = hit;
                var black = _expected?[column, row] ?? hit;
                extra += hit && !black ? 1 : 0;
                missing += !hit && black ? 1 : 0;
                if (black)
                {
                    counted++;
                    sum += pulses;
                    min = Math.Min(min, pulses);
                    max = Math.Max(max, pulses);
                }
            }
        }

        return new BurnReport
        {
            Burned = burned,
            Dose = dose,
            Pulses = Pulses,
            LaserOnTravelUm = TravelUm,
            LaserOnTravelCount = TravelPulses,
            DwellCount = StandCount,
            DwellSeconds = StandSeconds,
            LongestDwellSeconds = LongestStandSeconds,
            Dwells = _burnSpeedUmPerS is null ? null : new DwellFigures(DwellCount, DwellPulses),
            Edges = _edges?.Figures(_burnSpeedUmPerS!.Value, _xUm),
            PulsesPerPixel = counted == 0 ? new PulsesPerPixelFigures(0, 0, 0) : new PulsesPerPixelFigures(min, (double)sum / counted, max),
            RefusedMoves = refusedMoves,
            LaserOnSeconds = LaserOnSeconds,
            PulsesWhileMoving = MovingPulses,
            ExtraPixels = _expected is null ? 0 : extra,
            MissingPixels = _expected is null ? 0 : missing,
        };
    }

    // The last segment started by t (a segment starting within TimeEpsilon after t counts as started).
    private static int Advance(MotionSegment[] segments, int index, double t)
    {
        while (index + 1 < segments.Length && segments[index + 1].StartSeconds <= t + TimeEpsilon)
        {
            index++;
        }

        return index;
    }

    // When the motion of segments[index], current at t, next changes: its end if still ahead, else the next start.
    private static double NextChange(MotionSegment[] segments, int index, double t)
    {
        if (segments[index].EndSeconds > t + TimeEpsilon)
        {
            return segments[index].EndSeconds;
        }

        return index + 1 < segments.Length ? segments[index + 1].StartSeconds : double.PositiveInfinity;
    }

    // Velocity at t, read as the segment's start velocity when t falls within TimeEpsilon before its start.
    private static double VelocityAt(in MotionSegment segment, double t)
    {
        var dt = Math.Clamp(t - segment.StartSeconds, 0, segment.DurationSeconds);
        return dt >= segment.DurationSeconds ? 0 : segment.StartVelocity + (segment.Acceleration * dt);
    }

    [MethodImpl(HotPath.Optimized)]
    private void Pulse(in MotionSegment xSegment, in MotionSegment ySegment, double t, double hz)
    {
        Pulses++;
        var x = xSegment.PositionAt(t);
        var y = ySegment.PositionAt(t);
        var bandRow = CellAt(_rowEdges, y, _grid.OriginYMicrosteps);
        var (column, row) = Settle(x, y, CellAt(_columnEdges, x, _grid.OriginXMicrosteps), bandRow);
        var inGrid = InGrid(column, row);
        if (!inGrid || !(_expected?[column, row] ?? true))
        {
            TravelPulses++;
            TravelUm += _hasPrevious ? Math.Sqrt(Square((x - _previousX) * _xUm) + Square((y - _previousY) * _yUm)) : 0;
        }

        if (inGrid)
        {
            _dose[SubcellIndex(x, y, column, row)]++;
        }

        var vx = VelocityAt(xSegment, t);
        var vy = VelocityAt(ySegment, t);
        MovingPulses += vx != 0 || vy != 0 ? 1 : 0;
        if (_burnSpeedUmPerS is { } burn)
        {
            var speed = Math.Sqrt(Square(vx * _xUm) + Square(vy * _yUm));
            var dwell = speed < burn / 10;
            if (dwell)
            {
                DwellPulses++;
                DwellCount += _dwelling ? 0 : 1;
            }

            _dwelling = dwell;
            _edges?.Add(bandRow, x, hz);
        }

        _hasPrevious = true;
        _previousX = x;
        _previousY = y;
    }

    // The pixel a pulse at (x, y) marks: its own cell, unless that is white or off the grid and a black pixel's edge is
    // within half a microstep (the stage stands on a run's edge at both ends of a stop-go burn run).
    [MethodImpl(HotPath.Optimized)]
    private (int Column, int Row) Settle(double x, double y, int column, int row)
    {
        if (Black(column, row))
        {
            return (column, row);
        }

        var nearColumn = Near(_columnEdges, x, column);
        var nearRow = Near(_rowEdges, y, row);
        if (nearColumn != column && Black(nearColumn, row))
        {
            return (nearColumn, row);
        }

        if (nearRow != row && Black(column, nearRow))
        {
            return (column, nearRow);
        }

        return Black(nearColumn, nearRow) ? (nearColumn, nearRow) : (column, row);
    }

    // As BurnGrid.ColumnAt and RowCellAt, on the edges looked up once.
    [MethodImpl(HotPath.Optimized)]
    private int CellAt(long[] edges, double at, double origin)
    {
        var count = edges.Length - 1;
        if (at < edges[0])
        {
            return -1;
        }

        if (at >= edges[count])
        {
            return count;
        }

        var cell = (int)Math.Clamp(Math.Floor((at - origin) / _grid.PitchMicrosteps), 0, count - 1);
        while (cell > 0 && at < edges[cell])
        {
            cell--;
        }

        while (cell < count - 1 && at >= edges[cell + 1])
        {
            cell++;
        }

        return cell;
    }

    // The neighbour of `cell` (-1 and `count` are off the grid) whose shared edge `at` is within the snap of, or `cell`.
    private static int Near(long[] edges, double at, int cell)
    {
        var count = edges.Length - 1;
        if (cell >= 0 && at - edges[cell] <= EdgeSnapMicrosteps)
        {
            return cell - 1;
        }

        if (cell < count && edges[cell + 1] - at <= EdgeSnapMicrosteps)
        {
            return cell + 1;
        }

        return cell;
    }

    private bool InGrid(int column, int row) => column >= 0 && column < _grid.WidthPx && row >= 0 && row < _grid.HeightPx;

    private bool Black(int column, int row) => InGrid(column, row) && (_expected?[column, row] ?? true);

    [MethodImpl(HotPath.Optimized)]
    private long SubcellIndex(double x, double y, int column, int row)
    {
        const int n = DoseMap.SubcellsPerPixel;
        var i = Sub(x, _columnEdges[column], _columnEdges[column + 1]);
        var j = Sub(y, _rowEdges[row], _rowEdges[row + 1]);
        return ((((long)row * n) + j) * _grid.WidthPx * n) + ((long)column * n) + i;

        static int Sub(double at, long from, long to) => Math.Clamp((int)Math.Floor(n * (at - from) / (to - from)), 0, n - 1);
    }

    private void Stand(double seconds, double x0, double x1, double y0, double y1)
    {
        if (Math.Abs(x1 - x0) <= PositionEpsilon && Math.Abs(y1 - y0) <= PositionEpsilon)
        {
            _stand += seconds;
        }
        else
        {
            EndStand();
        }
    }

    private void EndStand()
    {
        if (_stand > 0)
        {
            LongestStandSeconds = Math.Max(LongestStandSeconds, _stand);
            if (_stand > _dwellToleranceSeconds)
            {
                StandCount++;
                StandSeconds += _stand;
            }
        }

        _stand = 0;
    }

    private static double Square(double v) => v * v;
}
