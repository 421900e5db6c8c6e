using LaserEngrave.Core.Imaging;
using LaserEngrave.Simulator.Motion;

namespace LaserEngrave.Simulator.Burn;

/// <summary>A move command the stage refused with an error reply.</summary>
/// <param name="AtSeconds">Simulation time of the refusal.</param>
/// <param name="Axis">The axis that refused.</param>
/// <param name="Command">The move's command number.</param>
/// <param name="ErrorCode">The error code replied.</param>
public readonly record struct RefusedMove(double AtSeconds, AxisName Axis, int Command, int ErrorCode);

/// <summary>Records when the laser fired and, with the axes' trajectories, works out what its pulses burned.</summary>
/// <remarks>
/// Times are seconds of simulation time, positions microsteps. The recorder keeps the laser's on/off changes and their
/// frequency; <see cref="Analyze"/> turns them into the Q-switch's pulse train (one pulse every 1 / f s from the instant
/// the laser switched on), lands each pulse at the stage's position at its instant, and reports what that burned
/// (docs/simulator.md, "The burn recorder"). It also keeps today's time-based stand counters: a laser-on stand (both
/// axes still) counts as a dwell once it lasts longer than the dwell tolerance, because completion-based replies leave
/// the laser standing at both ends of every burn run for a reply and a gate command (see
/// <see cref="SimulatorOptions.DwellTolerance"/>). Thread-safe.
/// </remarks>
public sealed class BurnRecorder
{
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

    /// <summary>The focus axis' trajectory; null on a two-axis machine.</summary>
    public AxisTrajectory? Z { get; init; }

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

    /// <summary>Every recorded switching on (frequency above 0) and off (0), in the order recorded, whatever <see cref="Restart"/> windowed: the twin's camera draws every burn the sample ever took.</summary>
    public IReadOnlyList<(double AtSeconds, double FrequencyHz)> LaserChanges
    {
        get
        {
            lock (_lock)
            {
                return [.. _laser];
            }
        }
    }

    /// <summary>The laser's frequency changed at <paramref name="atSeconds"/> (0 = off).</summary>
    /// <remarks>Only switching on and off is kept: a new frequency while the laser fires does not change its pulse train.</remarks>
    public void RecordLaser(double atSeconds, double frequencyHz)
    {
        if (!(frequencyHz >= 0 && double.IsFinite(frequencyHz)))
        {
            throw new ArgumentOutOfRangeException(nameof(frequencyHz), frequencyHz, "a laser frequency is 0 (off) or a finite number of Hz");
        }

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
    public IReadOnlyList<(double From, double To)> LaserOnIntervals(double untilSeconds) =>
        [.. LaserPeriods(untilSeconds).Select(p => (p.FromSeconds, p.ToSeconds))];

    /// <summary>Where the focus axis stood while the laser fired since <see cref="Restart"/>; null without a Z axis or without firing.</summary>
    public ZWhileFiring? FocusWhileFiring()
    {
        if (Z is not { } z)
        {
            return null;
        }

        MotionSegment[] zs = [.. z.Segments];
        var periods = LaserPeriods(_now?.Invoke() ?? LastInstant([.. X.Segments], [.. Y.Segments]));
        if (periods.Count == 0)
        {
            return null;
        }

        double min = double.PositiveInfinity, max = double.NegativeInfinity;
        var moving = 0;
        foreach (var period in periods)
        {
            foreach (var at in new[] { period.FromSeconds, period.ToSeconds })
            {
                var position = z.PositionAt(at);
                min = Math.Min(min, position);
                max = Math.Max(max, position);
            }

            // A Z segment in motion overlapping the period: the focus changed while the laser fired.
            if (zs.Any(s => (s.StartVelocity != 0 || s.Acceleration != 0) && s.StartSeconds < period.ToSeconds && s.EndSeconds > period.FromSeconds))
            {
                moving++;
            }
        }

        return new ZWhileFiring(min, max, moving, periods.Count);
    }

    /// <summary>Works out the burned image and the figures on <paramref name="grid"/>.</summary>
    /// <param name="grid">The job's pixel grid.</param>
    /// <param name="expected">The image that should have been burned (same size as the grid): white pixels make laser-on
    /// travel and extra pixels, its burn runs are where edges are measured.</param>
    /// <param name="burnSpeedMmPerS">The process' burn speed, mm/s: the pulse spacing at frequency f is this / f, and a pulse
    /// fired below a tenth of it is a dwell. Without it <see cref="BurnReport.Edges"/> and <see cref="BurnReport.Dwells"/> are null.</param>
    public BurnReport Analyze(BurnGrid grid, BitMask? expected = null, double? burnSpeedMmPerS = null)
    {
        ArgumentNullException.ThrowIfNull(grid);
        if (expected is not null && (expected.Width != grid.WidthPx || expected.Height != grid.HeightPx))
        {
            throw new ArgumentException($"the expected image is {expected.Width} x {expected.Height} px, the grid {grid.WidthPx} x {grid.HeightPx}", nameof(expected));
        }

        if (burnSpeedMmPerS is { } speed && !(speed > 0 && double.IsFinite(speed)))
        {
            throw new ArgumentOutOfRangeException(nameof(burnSpeedMmPerS), speed, "the burn speed must be above 0 mm/s");
        }

        MotionSegment[] xs = [.. X.Segments];
        MotionSegment[] ys = [.. Y.Segments];
        var until = _now?.Invoke() ?? LastInstant(xs, ys);
        var analysis = new PulseAnalysis(grid, expected, XMicrostepUm, YMicrostepUm, DwellTolerance.TotalSeconds, burnSpeedMmPerS);
        analysis.Walk(LaserPeriods(until), xs, ys);
        return analysis.Report(RefusedMoves.Count);
    }

    /// <summary>The pulses of a vector job against its paths: distance from the path, spacing, dwells, pulses off every path.</summary>
    /// <param name="paths">The paths that should be burned, in microsteps.</param>
    /// <param name="burnSpeedMmPerS">The process' burn speed, mm/s (the spacing it should give, and what counts as a dwell).</param>
    public PathReport AnalyzePaths(IReadOnlyList<LaserEngrave.Core.Vectors.StagePath> paths, double burnSpeedMmPerS)
    {
        ArgumentNullException.ThrowIfNull(paths);
        if (!(burnSpeedMmPerS > 0 && double.IsFinite(burnSpeedMmPerS)))
        {
            throw new ArgumentOutOfRangeException(nameof(burnSpeedMmPerS), burnSpeedMmPerS, "the burn speed must be above 0 mm/s");
        }

        MotionSegment[] xs = [.. X.Segments];
        MotionSegment[] ys = [.. Y.Segments];
        var until = _now?.Invoke() ?? LastInstant(xs, ys);
        return new PathAnalysis(paths, XMicrostepUm, YMicrostepUm).Analyze(LaserPeriods(until), X, Y, burnSpeedMmPerS);
    }

    // The laser-on periods inside the window, in time order, the last one ended at untilSeconds when still open.
    private List<LaserPeriod> LaserPeriods(double untilSeconds)
    {
        lock (_lock)
        {
            var periods = new List<LaserPeriod>();
            (double At, double Hz)? on = null;
            foreach (var (at, hz) in _laser.OrderBy(c => c.AtSeconds))
            {
                if (hz > 0)
                {
                    on ??= (at, hz);
                }
                else if (on is { } start)
                {
                    Add(start, at);
                    on = null;
                }
            }

            if (on is { } open)
            {
                Add(open, untilSeconds);
            }

            return periods;

            void Add((double At, double Hz) start, double off)
            {
                var from = Math.Max(start.At, _windowStart);
                var to = Math.Min(off, untilSeconds);
                if (to > from)
                {
                    periods.Add(new LaserPeriod(start.At, from, to, start.Hz));
                }
            }
        }
    }

    private double LastInstant(MotionSegment[] xs, MotionSegment[] ys)
    {
        lock (_lock)
        {
            var last = Math.Max(xs[^1].EndSeconds, ys[^1].EndSeconds);
            return _laser.Count > 0 ? Math.Max(last, _laser.Max(c => c.AtSeconds)) : last;
        }
    }
}
