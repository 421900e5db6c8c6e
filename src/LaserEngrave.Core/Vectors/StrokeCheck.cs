namespace LaserEngrave.Core.Vectors;

/// <summary>
/// A stroke's model checked against its path while the laser is on, piece by piece of its motion rather than at sampled
/// instants: between two commands (and the ends of the axes' ramps) each axis moves on a parabola, so its speed and its
/// distance from a segment's line are quadratics in time whose extremes are found in closed form.
/// </summary>
/// <remarks>
/// The distance checked is <see cref="StrokeProfile.DistanceFollowing"/>'s: from the model's position to the path's
/// segments in a window about the ideal point. Its upper bound on a piece is the distance to one segment of that window,
/// the one whose part of the plane (between the bisectors of its two corners) holds the model, found by a cursor that
/// walks the path forward as the model crosses those bisectors. The bound is checked against the true distance where
/// it could raise the largest deviation or decide a split, and a piece whose bound is not met there (the model outside a
/// corner, another part of the path nearer) is halved until bound and distance agree. So a deviation between two of the
/// old 0.25 ms samples is found too, and the work grows with the commands and the vertices passed, not the burn time.
/// </remarks>
internal sealed class StrokeCheck
{
    /// <summary>The old check's step: its model sampled this often while the laser is on.</summary>
    public const double SampleSeconds = 0.00025;

    // Bound and measured distance agree within this, microsteps (1 nm): far below any figure shown.
    private const double Agreement = 0.01;

    // A piece undecided against the limit is halved at most this often (to parts of a few microseconds); what is left is
    // taken at its bound (never less than the truth).
    private const int MaxDepth = 12;

    // A piece decided against the limit is halved at most this often for the largest deviation's figure, then taken at its bound.
    private const int FigureDepth = 3;

    private readonly StrokeProfile _ideal;
    private readonly double _acceleration;
    private readonly double _limit;
    private readonly double _speed;
    private readonly double _speedTolerance;
    private readonly double _window;
    private readonly double _pathStart;
    private readonly double _pathEnd;
    private readonly List<double> _worst = [];
    private long _budget;
    private int _segment;
    private bool _over;
    private (double Badness, double At) _peak;

    private StrokeCheck(StrokeProfile ideal, double acceleration, double limit, double speed, double speedTolerance, double window, double pathStart, double pathEnd)
    {
        _ideal = ideal;
        _acceleration = acceleration;
        _limit = limit;
        _speed = speed;
        _speedTolerance = speedTolerance;
        _window = window;
        _pathStart = pathStart;
        _pathEnd = pathEnd;
    }

    /// <summary>The largest distance of the model from the path with the laser on, microsteps.</summary>
    public double Largest { get; private set; }

    /// <summary>
    /// Whether the check gave up: a path whose segments are so short and so many (a spiral of 500 000 vertices 5 mm wide)
    /// that its pieces would take more measurements than sampling every 0.25 ms; the stroke is then sampled as before.
    /// </summary>
    public bool GaveUp { get; private set; }

    /// <summary>Per stretch where the model leaves the path too far or runs off the burn speed, where along the path it was worst.</summary>
    public IReadOnlyList<double> Worst => _worst;

    /// <summary>Checks the model of the axes under <paramref name="xs"/> and <paramref name="ys"/> (each in time order) from <paramref name="on"/> to <paramref name="off"/>.</summary>
    public static StrokeCheck Run(
        StrokeProfile ideal,
        List<AxisCommand> xs,
        List<AxisCommand> ys,
        StagePoint start,
        double on,
        double off,
        double acceleration,
        double limit,
        double speedTolerance,
        double window,
        double pathStart,
        double pathEnd)
    {
        var check = new StrokeCheck(ideal, acceleration, limit, ideal.Speed, speedTolerance, window, pathStart, pathEnd)
        {
            // Twice the samples at 0.25 ms, counting every part and every measurement.
            _budget = 64 + (long)(2 * Math.Max(0, off - on) / SampleSeconds),
        };

        try
        {
            check.Follow(xs, ys, start, on, off);
        }
        catch (BudgetSpent)
        {
            check.GaveUp = true;
        }

        return check;
    }

    private void Follow(List<AxisCommand> xs, List<AxisCommand> ys, StagePoint start, double on, double off)
    {
        if (!(on <= off))
        {
            return;
        }

        var x = new AxisModel(start.X, _acceleration);
        var y = new AxisModel(start.Y, _acceleration);
        int xi = 0, yi = 0;
        var t = on;
        Apply(ref x, xs, ref xi, t);
        Apply(ref y, ys, ref yi, t);
        _segment = _ideal.SegmentAt(_ideal.DistanceAt(t));
        while (true)
        {
            var next = off;
            next = xi < xs.Count ? Math.Min(next, xs[xi].AtSeconds) : next;
            next = yi < ys.Count ? Math.Min(next, ys[yi].AtSeconds) : next;
            Interval(x, y, t, Math.Max(t, next));
            if (next >= off)
            {
                break;
            }

            Apply(ref x, xs, ref xi, next);
            Apply(ref y, ys, ref yi, next);
            t = next;
        }

        if (_over)
        {
            _worst.Add(_peak.At);
        }
    }

    // Every command up to a time carried out, and the axis advanced to it (as the sampled model did at each instant).
    private static void Apply(ref AxisModel axis, List<AxisCommand> commands, ref int index, double seconds)
    {
        while (index < commands.Count && commands[index].AtSeconds <= seconds)
        {
            axis.Apply(commands[index++]);
        }

        axis.AdvanceTo(seconds);
    }

    // From one command to the next: cut where an axis ends its ramp, so that each part is one parabola per axis.
    private void Interval(AxisModel x, AxisModel y, double from, double to)
    {
        var ax = Parabola.Of(x, _acceleration);
        var ay = Parabola.Of(y, _acceleration);
        var t = from;
        do
        {
            var end = to;
            end = ax.RampEnd > t && ax.RampEnd < end ? ax.RampEnd : end;
            end = ay.RampEnd > t && ay.RampEnd < end ? ay.RampEnd : end;
            Piece(ax, ay, t, end);
            ax = ax.At(end);
            ay = ay.At(end);
            t = end;
        }
        while (t < to);
    }

    // One parabola per axis from t0 to t1: walk the path's segments the model passes, each part bounded and checked.
    private void Piece(Parabola ax, Parabola ay, double t0, double t1)
    {
        var bisectors = Math.Max(4, 2 * (_ideal.VertexCount + 8));
        var stalled = 0;
        var t = t0;
        while (true)
        {
            // A model right on a bisector may be found on both sides of it by rounding: after a few crossings without
            // moving on, the cursor stays for the rest of the piece (its segment's bound holds all the same).
            if (stalled > 2)
            {
                bisectors = 0;
            }

            // The next crossing of a bisector by the model: into the next segment (forward) or back into the one before.
            var end = t1;
            var next = _segment;
            if (_segment + 1 <= _ideal.VertexCount - 2 && bisectors > 0)
            {
                var crossing = Crossing(_segment + 1, ax, ay, t, t1, forward: true);
                if (crossing < end)
                {
                    (end, next) = (crossing, _segment + 1);
                }
            }

            if (_segment >= 1 && bisectors > 0)
            {
                var crossing = Crossing(_segment, ax, ay, t, end, forward: false);
                if (crossing < end)
                {
                    (end, next) = (crossing, _segment - 1);
                }
            }

            if (end > t || end >= t1)
            {
                Part(ax, ay, t, end);
            }

            if (end >= t1)
            {
                return;
            }

            stalled = end > t ? 0 : stalled + 1;
            _segment = next;
            bisectors--;
            t = end;
        }
    }

    // A part of a piece on one segment: its deviation bound checked where it matters, its speed error in closed form, both observed.
    private void Part(Parabola ax, Parabola ay, double t0, double t1)
    {
        Spend();
        var (deviation, deviationAt) = Deviation(ax, ay, t0, t1, 0);
        var (speedError, speedAt) = SpeedError(ax, ay, t0, t1);
        Largest = Math.Max(Largest, deviation);
        if (deviation > _limit || speedError > _speedTolerance)
        {
            _over = true;
            var byDeviation = deviation / _limit;
            var bySpeed = speedError / _speedTolerance;
            var badness = Math.Max(byDeviation, bySpeed);
            if (badness > _peak.Badness)
            {
                _peak = (badness, _ideal.DistanceAt(byDeviation >= bySpeed ? deviationAt : speedAt) - _pathStart);
            }
        }
        else if (_over)
        {
            _worst.Add(_peak.At);
            (_over, _peak) = (false, (0, 0));
        }
    }

    // The largest distance from the window's segments on [t0, t1]: the bound by the cursor's segment, met by a measurement
    // where it could raise the largest or cross the limit, else halved. Returns the value (within Agreement of the truth) and when.
    private (double Value, double At) Deviation(Parabola ax, Parabola ay, double t0, double t1, int depth)
    {
        var (bound, at) = SegmentBound(_segment, ax, ay, t0, t1);
        if (bound <= _limit && bound <= Largest + Agreement)
        {
            return (Math.Min(bound, Largest), at);
        }

        var low = Measure(ax, ay, at);
        var lowAt = at;
        if (bound - low <= Agreement)
        {
            return (bound, at);
        }

        // The cursor's segment not the nearest there (left behind, or out of the window): the cursor moves to the nearest.
        var s = _ideal.DistanceAt(at);
        var nearest = _ideal.NearestSegment(ax.Position(at), ay.Position(at), Math.Max(_pathStart, s - _window), Math.Min(_pathEnd, s + _window));
        if (nearest >= 0 && nearest != _segment)
        {
            var (again, againAt) = SegmentBound(nearest, ax, ay, t0, t1);
            if (again < bound)
            {
                (_segment, bound, at) = (nearest, again, againAt);
                if (bound <= _limit && bound <= Largest + Agreement)
                {
                    return (Math.Min(bound, Largest), at);
                }

                if (bound - low <= Agreement)
                {
                    return (bound, at);
                }
            }
        }

        var middle = 0.5 * (t0 + t1);
        if (low <= _limit && bound > _limit)
        {
            // Undecided against the limit and the bound loose here (another part of the path nearer, the model outside a
            // corner): the distance changes no faster than the model moves, which decides it as the part is halved.
            var atMiddle = Measure(ax, ay, middle);
            var moving = Math.Sqrt(ax.SpeedSquaredMax(t0, t1)) + Math.Sqrt(ay.SpeedSquaredMax(t0, t1));
            var lipschitz = atMiddle + (moving * (t1 - t0) / 2);
            if (atMiddle > low)
            {
                (low, lowAt) = (atMiddle, middle);
            }

            if (lipschitz < bound)
            {
                (bound, at) = (lipschitz, middle);
            }

            if (bound - low <= Agreement)
            {
                return (bound, at);
            }

            if (low <= _limit && bound > _limit)
            {
                return depth >= MaxDepth ? (bound, at) : Halves(ax, ay, t0, middle, t1, depth, low);
            }
        }

        // Decided against the limit: halved only while the largest could still rise, a few times (the figure, not the decision).
        if (bound <= Math.Max(Largest, low) + Agreement)
        {
            return (Math.Max(low, Math.Min(bound, Largest)), lowAt);
        }

        return depth >= FigureDepth ? (bound, at) : Halves(ax, ay, t0, middle, t1, depth, low);
    }

    private (double Value, double At) Halves(Parabola ax, Parabola ay, double t0, double middle, double t1, int depth, double low)
    {
        Largest = Math.Max(Largest, low);
        var left = Deviation(ax, ay, t0, middle, depth + 1);
        Largest = Math.Max(Largest, left.Value);
        var right = Deviation(ax, ay, middle, t1, depth + 1);
        return right.Value > left.Value ? right : left;
    }

    // The true distance at one instant, as the sampled check measured it.
    private double Measure(Parabola ax, Parabola ay, double t)
    {
        Spend();
        var s = _ideal.DistanceAt(t);
        return _ideal.DistanceFollowing(ax.Position(t), ay.Position(t), Math.Max(_pathStart, s - _window), Math.Min(_pathEnd, s + _window));
    }

    private void Spend()
    {
        if (--_budget < 0)
        {
            throw new BudgetSpent();
        }
    }

    // The largest distance from one segment on [t0, t1] (that segment in the window throughout): across its line and past its ends.
    private (double Value, double At) SegmentBound(int segment, Parabola ax, Parabola ay, double t0, double t1)
    {
        double InWindowFrom(double t) => Math.Max(_pathStart, _ideal.DistanceAt(t) - _window);
        double InWindowTo(double t) => Math.Min(_pathEnd, _ideal.DistanceAt(t) + _window);
        if (!_ideal.InWindow(segment, InWindowFrom(t0), InWindowTo(t0)) || !_ideal.InWindow(segment, InWindowFrom(t1), InWindowTo(t1)))
        {
            return (double.PositiveInfinity, 0.5 * (t0 + t1));
        }

        var (x0, y0) = _ideal.Vertex(segment);
        var (x1, y1) = _ideal.Vertex(segment + 1);
        double dx = x1 - x0, dy = y1 - y0;
        var length = Math.Sqrt((dx * dx) + (dy * dy));
        if (length == 0)
        {
            return (double.PositiveInfinity, 0.5 * (t0 + t1));
        }

        double ux = dx / length, uy = dy / length;

        // Across: n . (P - a) with n = (-uy, ux); along: u . (P - a). Both quadratics in time on the part.
        var across = Quadratic.Combine(ax, ay, -uy, ux, x0, y0, t0);
        var along = Quadratic.Combine(ax, ay, ux, uy, x0, y0, t0);
        var h = t1 - t0;
        var (acrossMax, acrossAt) = across.AbsMax(h);
        var (alongMin, alongMax) = along.Range(h);
        var past = Math.Max(0, Math.Max(-alongMin, alongMax - length));
        return (Math.Sqrt((acrossMax * acrossMax) + (past * past)), t0 + acrossAt);
    }

    // The spot's speed error on [t0, t1]: |v|^2 is a quadratic in time, largest at an end, smallest at an end or its vertex.
    private (double Error, double At) SpeedError(Parabola ax, Parabola ay, double t0, double t1)
    {
        double vx = ax.Velocity(t0), vy = ay.Velocity(t0);
        var q = new Quadratic((vx * vx) + (vy * vy), 2 * ((vx * ax.A) + (vy * ay.A)), (ax.A * ax.A) + (ay.A * ay.A));
        var h = t1 - t0;
        var (low, lowAt) = q.Min(h);
        var high = Math.Max(q.Value(0), q.Value(h));
        var highAt = q.Value(0) >= q.Value(h) ? 0 : h;
        var fast = Math.Abs((Math.Sqrt(Math.Max(high, 0)) / _speed) - 1);
        var slow = Math.Abs((Math.Sqrt(Math.Max(low, 0)) / _speed) - 1);
        return fast >= slow ? (fast, t0 + highAt) : (slow, t0 + lowAt);
    }

    // When the model first crosses the bisector at vertex `vertex` on (t0, t1]: forward into the segment after it, or back before it.
    private double Crossing(int vertex, Parabola ax, Parabola ay, double t0, double t1, bool forward)
    {
        var (px, py) = _ideal.Vertex(vertex - 1);
        var (cx, cy) = _ideal.Vertex(vertex);
        var (nx, ny) = _ideal.Vertex(vertex + 1);
        double ix = cx - px, iy = cy - py, ox = nx - cx, oy = ny - cy;
        double li = Math.Sqrt((ix * ix) + (iy * iy)), lo = Math.Sqrt((ox * ox) + (oy * oy));
        if (li == 0 || lo == 0)
        {
            return double.PositiveInfinity;
        }

        // The bisector's normal: the mean of the directions in and out (the incoming one where the path turns back).
        double bx = (ix / li) + (ox / lo), by = (iy / li) + (oy / lo);
        if (Math.Sqrt((bx * bx) + (by * by)) < 1e-9)
        {
            (bx, by) = (ix / li, iy / li);
        }

        var side = Quadratic.Combine(ax, ay, bx, by, cx, cy, t0);
        if (!forward)
        {
            side = side.Negated();
        }

        // Past the bisector (forward) or back over it: the quadratic turns positive.
        var h = t1 - t0;
        if (side.Value(0) > 0)
        {
            return t0;
        }

        var root = side.FirstRise(h);
        return root is { } r ? t0 + r : double.PositiveInfinity;
    }

    private sealed class BudgetSpent : Exception;

    /// <summary>One axis from a time on: position, velocity and acceleration, until its ramp (if any) ends.</summary>
    private readonly record struct Parabola(double T, double P, double V, double A, double Command, bool Stopping, double RampEnd)
    {
        public static Parabola Of(AxisModel axis, double acceleration)
        {
            var dv = axis.Command - axis.Velocity;
            return dv == 0
                ? new Parabola(axis.Time, axis.Position, axis.Velocity, 0, axis.Command, axis.Stopping, double.PositiveInfinity)
                : new Parabola(axis.Time, axis.Position, axis.Velocity, Math.Sign(dv) * acceleration, axis.Command, axis.Stopping, axis.Time + (Math.Abs(dv) / acceleration));
        }

        public double Position(double t)
        {
            var dt = t - T;
            return P + (V * dt) + (0.5 * A * dt * dt);
        }

        public double Velocity(double t) => V + (A * (t - T));

        public double SpeedSquaredMax(double t0, double t1) => Math.Max(Velocity(t0) * Velocity(t0), Velocity(t1) * Velocity(t1));

        /// <summary>The axis at a later time of the same piece; at its ramp's end the commanded speed (and a stop's whole microstep, as the model rounds it).</summary>
        public Parabola At(double t)
        {
            if (t >= RampEnd)
            {
                var position = Position(RampEnd) + (Command * (t - RampEnd));
                if (Stopping && Command == 0)
                {
                    position = Math.Round(Position(RampEnd), MidpointRounding.AwayFromZero);
                }

                return new Parabola(t, position, Command, 0, Command, Stopping && Command != 0, double.PositiveInfinity);
            }

            return this with { T = t, P = Position(t), V = Velocity(t) };
        }
    }

    /// <summary>c0 + c1 t + c2 t^2 on [0, h].</summary>
    private readonly record struct Quadratic(double C0, double C1, double C2)
    {
        /// <summary>w . (P(t0 + t) - c) for the direction w = (wx, wy): each axis' parabola from t0.</summary>
        public static Quadratic Combine(Parabola ax, Parabola ay, double wx, double wy, double cx, double cy, double t0) =>
            new(
                (wx * (ax.Position(t0) - cx)) + (wy * (ay.Position(t0) - cy)),
                (wx * ax.Velocity(t0)) + (wy * ay.Velocity(t0)),
                0.5 * ((wx * ax.A) + (wy * ay.A)));

        public double Value(double t) => C0 + (t * (C1 + (t * C2)));

        public Quadratic Negated() => new(-C0, -C1, -C2);

        public (double Value, double At) AbsMax(double h)
        {
            var (best, at) = Math.Abs(Value(0)) >= Math.Abs(Value(h)) ? (Math.Abs(Value(0)), 0.0) : (Math.Abs(Value(h)), h);
            if (C2 != 0)
            {
                var vertex = -C1 / (2 * C2);
                if (vertex > 0 && vertex < h && Math.Abs(Value(vertex)) > best)
                {
                    (best, at) = (Math.Abs(Value(vertex)), vertex);
                }
            }

            return (best, at);
        }

        public (double Min, double Max) Range(double h)
        {
            double a = Value(0), b = Value(h);
            double min = Math.Min(a, b), max = Math.Max(a, b);
            if (C2 != 0)
            {
                var vertex = -C1 / (2 * C2);
                if (vertex > 0 && vertex < h)
                {
                    var v = Value(vertex);
                    (min, max) = (Math.Min(min, v), Math.Max(max, v));
                }
            }

            return (min, max);
        }

        public (double Value, double At) Min(double h)
        {
            var (best, at) = Value(0) <= Value(h) ? (Value(0), 0.0) : (Value(h), h);
            if (C2 > 0)
            {
                var vertex = -C1 / (2 * C2);
                if (vertex > 0 && vertex < h && Value(vertex) < best)
                {
                    (best, at) = (Value(vertex), vertex);
                }
            }

            return (best, at);
        }

        /// <summary>The first t in (0, h] where the quadratic (not positive at 0) turns positive, if it does.</summary>
        public double? FirstRise(double h)
        {
            if (C2 == 0)
            {
                if (C1 <= 0)
                {
                    return null;
                }

                var t = -C0 / C1;
                return t <= h ? Math.Max(t, 0) : null;
            }

            var discriminant = (C1 * C1) - (4 * C2 * C0);
            if (discriminant < 0)
            {
                return null;
            }

            // Both roots, the smaller first, computed without cancellation.
            var sq = Math.Sqrt(discriminant);
            var qq = -0.5 * (C1 + (C1 >= 0 ? sq : -sq));
            double r1 = qq / C2, r2 = qq != 0 ? C0 / qq : r1;
            var (first, second) = r1 <= r2 ? (r1, r2) : (r2, r1);
            // A rise: the value just after the root is positive (a touch that stays at or below zero is no crossing).
            if (Rises(first, h))
            {
                return first;
            }

            if (Rises(second, h))
            {
                return second;
            }

            return Value(h) > 0 ? h : null;
        }

        private bool Rises(double root, double h) =>
            root >= 0 && root <= h && Value(Math.Min(h, root + Math.Max(1e-12, Math.Abs(root) * 1e-9))) > 0;
    }
}
