using LaserEngrave.Core.Imaging;
using LaserEngrave.Simulator.Motion;

namespace LaserEngrave.Simulator.Burn;

/// <summary>A move command the stage refused with an error reply.</summary>
/// <param name="AtSeconds">Simulation time of the refusal.</param>
/// <param name="Axis">The axis that refused.</param>
/// <param name="Command">The move's command number.</param>
/// <param name="ErrorCode">The error code replied.</param>
public readonly record struct RefusedMove(double AtSeconds, AxisName Axis, int Command, int ErrorCode);

/// <summary>Records when the laser fired and, with the axes' trajectories, works out what was burned.</summary>
/// <remarks>
/// Times are seconds of simulation time, positions microsteps. The analysis cuts every laser-on interval at each
/// change of either axis' motion segment, so within a piece each axis moves one way at most:
/// <list type="bullet">
/// <item>X moving, Y standing on a row's centre line: the row is covered over that x span; any part of it over a pixel
/// the expected image has white, or outside the grid, is laser-on travel.</item>
/// <item>X moving with Y anywhere else, or Y moving: all of it is laser-on travel.</item>
/// <item>Both still: dwell; a stand counts once it lasts longer than the dwell tolerance, because completion-based
/// replies leave the laser standing at both ends of every burn run for a reply and a gate command (see
/// <see cref="SimulatorOptions.DwellTolerance"/>).</item>
/// </list>
/// Thread-safe.
/// </remarks>
public sealed class BurnRecorder
{
    private const double Epsilon = 1e-6;

    private readonly Lock _lock = new();
    private readonly List<(double AtSeconds, double FrequencyHz)> _laser = [];
    private readonly List<RefusedMove> _refused = [];
    private readonly Func<double>? _now;
    private double _windowStart = double.NegativeInfinity;

    /// <param name="x">The X axis' trajectory.</param>
    /// <param name="y">The Y axis' trajectory.</param>
    /// <param name="xMicrostepUm">Length of an X microstep, µm.</param>
    /// <param name="yMicrostepUm">Length of a Y microstep, µm.</param>
    /// <param name="dwellTolerance">Stands up to this long are not dwell; <see cref="SimulatorOptions.DwellTolerance"/> by default.</param>
    /// <param name="now">Current simulation time, to close an interval still open; without it, the last recorded instant.</param>
    public BurnRecorder(AxisTrajectory x, AxisTrajectory y, double xMicrostepUm, double yMicrostepUm, TimeSpan? dwellTolerance = null, Func<double>? now = null)
    {
        ArgumentNullException.ThrowIfNull(x);
        ArgumentNullException.ThrowIfNull(y);
        X = x;
        Y = y;
        XMicrostepUm = xMicrostepUm;
        YMicrostepUm = yMicrostepUm;
        DwellTolerance = dwellTolerance ?? new SimulatorOptions().DwellTolerance;
        _now = now;
    }

    public AxisTrajectory X { get; }

    public AxisTrajectory Y { get; }

    public double XMicrostepUm { get; }

    public double YMicrostepUm { get; }

    public TimeSpan DwellTolerance { get; }

    /// <summary>Move commands refused since the last <see cref="Restart"/>.</summary>
    public IReadOnlyList<RefusedMove> RefusedMoves
    {
        get
        {
            lock (_lock)
            {
                return [.. _refused];
            }
        }
    }

    /// <summary>Whether the laser fires now, as last recorded.</summary>
    public bool LaserOn
    {
        get
        {
            lock (_lock)
            {
                return _laser.Count > 0 && _laser[^1].FrequencyHz > 0;
            }
        }
    }

    /// <summary>The laser's frequency changed at <paramref name="atSeconds"/> (0 = off).</summary>
    public void RecordLaser(double atSeconds, double frequencyHz)
    {
        lock (_lock)
        {
            var on = frequencyHz > 0;
            if (_laser.Count > 0 && _laser[^1].FrequencyHz > 0 == on)
            {
                return;
            }

            _laser.Add((atSeconds, frequencyHz));
        }
    }

    public void RecordRefusedMove(RefusedMove refused)
    {
        lock (_lock)
        {
            _refused.Add(refused);
        }
    }

    /// <summary>Starts a new job: only what happens from now on counts (the trajectories keep their history).</summary>
    public void Restart(double atSeconds)
    {
        lock (_lock)
        {
            _windowStart = atSeconds;
            _refused.Clear();
        }
    }

    /// <summary>The laser-on intervals, ended at <paramref name="untilSeconds"/> when still open.</summary>
    public IReadOnlyList<(double From, double To)> LaserOnIntervals(double untilSeconds)
    {
        lock (_lock)
        {
            var intervals = new List<(double, double)>();
            double? on = null;
            foreach (var (at, hz) in _laser.OrderBy(c => c.AtSeconds))
            {
                if (hz > 0)
                {
                    on ??= at;
                }
                else if (on is { } from)
                {
                    Add(from, at);
                    on = null;
                }
            }

            if (on is { } open)
            {
                Add(open, untilSeconds);
            }

            return intervals;

            void Add(double from, double to)
            {
                from = Math.Max(from, _windowStart);
                to = Math.Min(to, untilSeconds);
                if (to > from)
                {
                    intervals.Add((from, to));
                }
            }
        }
    }

    /// <summary>Works out the burned image and the counters on <paramref name="grid"/>.</summary>
    /// <param name="grid">The job's pixel grid.</param>
    /// <param name="expected">The image that should have been burned (same size as the grid), to find laser-on travel over white.</param>
    public BurnReport Analyze(BurnGrid grid, BitMask? expected = null)
    {
        ArgumentNullException.ThrowIfNull(grid);
        if (expected is not null && (expected.Width != grid.WidthPx || expected.Height != grid.HeightPx))
        {
            throw new ArgumentException($"the expected image is {expected.Width} x {expected.Height} px, the grid {grid.WidthPx} x {grid.HeightPx}", nameof(expected));
        }

        var xs = X.Segments;
        var ys = Y.Segments;
        var until = _now?.Invoke() ?? LastInstant(xs, ys);
        var analysis = new Analysis(grid, expected, XMicrostepUm, YMicrostepUm, DwellTolerance.TotalSeconds);
        foreach (var (from, to) in LaserOnIntervals(until))
        {
            analysis.LaserOnSeconds += to - from;
            var cuts = new SortedSet<double> { from, to };
            AddCuts(cuts, xs, from, to);
            AddCuts(cuts, ys, from, to);
            var times = cuts.ToArray();
            for (var i = 0; i + 1 < times.Length; i++)
            {
                var (t0, t1) = (times[i], times[i + 1]);
                analysis.Piece(t1 - t0, PositionAt(xs, t0), PositionAt(xs, t1), PositionAt(ys, t0), PositionAt(ys, t1));
            }

            analysis.EndInterval();
        }

        var burned = analysis.Burned();
        long extra = 0, missing = 0;
        if (expected is not null)
        {
            for (var row = 0; row < grid.HeightPx; row++)
            {
                for (var column = 0; column < grid.WidthPx; column++)
                {
                    extra += burned[column, row] && !expected[column, row] ? 1 : 0;
                    missing += !burned[column, row] && expected[column, row] ? 1 : 0;
                }
            }
        }

        return new BurnReport
        {
            Burned = burned,
            LaserOnTravelUm = analysis.TravelUm,
            LaserOnTravelCount = analysis.TravelCount,
            DwellCount = analysis.DwellCount,
            DwellSeconds = analysis.DwellSeconds,
            LongestDwellSeconds = analysis.LongestDwellSeconds,
            RefusedMoves = RefusedMoves.Count,
            LaserOnSeconds = analysis.LaserOnSeconds,
            ExtraPixels = extra,
            MissingPixels = missing,
        };
    }

    private double LastInstant(IReadOnlyList<MotionSegment> xs, IReadOnlyList<MotionSegment> ys)
    {
        lock (_lock)
        {
            var last = Math.Max(xs[^1].EndSeconds, ys[^1].EndSeconds);
            return _laser.Count > 0 ? Math.Max(last, _laser.Max(c => c.AtSeconds)) : last;
        }
    }

    // Adds the starts and ends of the segments that change motion strictly inside (from, to).
    private static void AddCuts(SortedSet<double> cuts, IReadOnlyList<MotionSegment> segments, double from, double to)
    {
        for (var i = IndexAt(segments, from); i < segments.Count && segments[i].StartSeconds < to; i++)
        {
            foreach (var t in (ReadOnlySpan<double>)[segments[i].StartSeconds, segments[i].EndSeconds])
            {
                if (t > from && t < to)
                {
                    cuts.Add(t);
                }
            }
        }
    }

    private static double PositionAt(IReadOnlyList<MotionSegment> segments, double t) => segments[IndexAt(segments, t)].PositionAt(t);

    // The last segment started by t (the first for earlier t); segments are in start order.
    private static int IndexAt(IReadOnlyList<MotionSegment> segments, double t)
    {
        int lo = 0, hi = segments.Count - 1;
        while (lo < hi)
        {
            var mid = (lo + hi + 1) / 2;
            if (segments[mid].StartSeconds <= t)
            {
                lo = mid;
            }
            else
            {
                hi = mid - 1;
            }
        }

        return lo;
    }

    /// <summary>The running sums of one analysis.</summary>
    private sealed class Analysis(BurnGrid grid, BitMask? expected, double xUm, double yUm, double dwellTolerance)
    {
        private readonly List<(double Lo, double Hi)>[] _cover = new List<(double, double)>[grid.HeightPx];
        private double _stand;
        private bool _travelling;

        public double TravelUm { get; private set; }

        public int TravelCount { get; private set; }

        public int DwellCount { get; private set; }

        public double DwellSeconds { get; private set; }

        public double LongestDwellSeconds { get; private set; }

        public double LaserOnSeconds { get; set; }

        public void Piece(double seconds, double x0, double x1, double y0, double y1)
        {
            var xMoves = Math.Abs(x1 - x0) > Epsilon;
            var yMoves = Math.Abs(y1 - y0) > Epsilon;
            if (!xMoves && !yMoves)
            {
                _stand += seconds;
                return;
            }

            EndStand();
            double travel;
            if (yMoves)
            {
                travel = Math.Sqrt(Square((x1 - x0) * xUm) + Square((y1 - y0) * yUm));
            }
            else
            {
                var (lo, hi) = x0 < x1 ? (x0, x1) : (x1, x0);
                var line = Math.Round(y0);
                var row = Math.Abs(y0 - line) <= Epsilon ? grid.RowAt((long)line) : -1;
                if (row < 0)
                {
                    travel = (hi - lo) * xUm;
                }
                else
                {
                    (_cover[row] ??= []).Add((lo, hi));
                    travel = OverWhite(row, lo, hi) * xUm;
                }
            }

            var travelling = travel > Epsilon;
            if (travelling)
            {
                TravelUm += travel;
                TravelCount += _travelling ? 0 : 1;
            }

            _travelling = travelling;
        }

        public void EndInterval()
        {
            EndStand();
            _travelling = false;
        }

        public BitMask Burned()
        {
            var mask = new BitMask(grid.WidthPx, grid.HeightPx);
            var covered = new double[grid.WidthPx];
            for (var row = 0; row < grid.HeightPx; row++)
            {
                if (_cover[row] is not { } spans)
                {
                    continue;
                }

                Array.Clear(covered);
                foreach (var (lo, hi) in Merge(spans))
                {
                    for (var column = Math.Max(0, grid.ColumnAt(lo)); column < grid.WidthPx && grid.ColumnEdge(column) < hi; column++)
                    {
                        covered[column] += Overlap(lo, hi, grid.ColumnEdge(column), grid.ColumnEdge(column + 1));
                    }
                }

                for (var column = 0; column < grid.WidthPx; column++)
                {
                    var width = grid.ColumnEdge(column + 1) - grid.ColumnEdge(column);
                    mask[column, row] = width > 0 && covered[column] >= (width / 2.0) - Epsilon;
                }
            }

            return mask;
        }

        private static double Square(double v) => v * v;

        private static double Overlap(double lo, double hi, double from, double to) => Math.Max(0, Math.Min(hi, to) - Math.Max(lo, from));

        private static List<(double Lo, double Hi)> Merge(List<(double Lo, double Hi)> spans)
        {
            spans.Sort();
            var merged = new List<(double Lo, double Hi)>();
            foreach (var span in spans)
            {
                if (merged.Count > 0 && span.Lo <= merged[^1].Hi)
                {
                    merged[^1] = (merged[^1].Lo, Math.Max(merged[^1].Hi, span.Hi));
                }
                else
                {
                    merged.Add(span);
                }
            }

            return merged;
        }

        // Length of [lo, hi] outside the grid or over pixels the expected image has white.
        private double OverWhite(int row, double lo, double hi)
        {
            double left = grid.ColumnEdge(0), right = grid.ColumnEdge(grid.WidthPx);
            var white = Overlap(lo, hi, double.NegativeInfinity, left) + Overlap(lo, hi, right, double.PositiveInfinity);
            if (expected is null)
            {
                return white;
            }

            for (var column = Math.Max(0, grid.ColumnAt(lo)); column < grid.WidthPx && grid.ColumnEdge(column) < hi; column++)
            {
                if (!expected[column, row])
                {
                    white += Overlap(lo, hi, grid.ColumnEdge(column), grid.ColumnEdge(column + 1));
                }
            }

            return white;
        }

        private void EndStand()
        {
            if (_stand > 0)
            {
                LongestDwellSeconds = Math.Max(LongestDwellSeconds, _stand);
                if (_stand > dwellTolerance)
                {
                    DwellCount++;
                    DwellSeconds += _stand;
                }
            }

            _stand = 0;
        }
    }
}
