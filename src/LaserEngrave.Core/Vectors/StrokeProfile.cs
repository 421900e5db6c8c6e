namespace LaserEngrave.Core.Vectors;

/// <summary>
/// The ideal motion of a stroke: along a polyline (run-up, path, run-out) from rest, at a constant acceleration up
/// to the burn speed, at that speed, and braking to rest at the end; positions in microsteps, times from 0.
/// </summary>
internal sealed class StrokeProfile
{
    private readonly double[] _x;
    private readonly double[] _y;
    private readonly double[] _s;

    public StrokeProfile(IReadOnlyList<(double X, double Y)> points, double speed, double acceleration)
    {
        _x = new double[points.Count];
        _y = new double[points.Count];
        _s = new double[points.Count];
        for (var i = 0; i < points.Count; i++)
        {
            (_x[i], _y[i]) = points[i];
            _s[i] = i == 0 ? 0 : _s[i - 1] + Math.Sqrt(Sq(_x[i] - _x[i - 1]) + Sq(_y[i] - _y[i - 1]));
        }

        Speed = speed;
        Acceleration = acceleration;
        Length = _s[^1];
        RampSeconds = speed / acceleration;
        RampLength = speed * speed / (2 * acceleration);
        DurationSeconds = (Length / speed) + RampSeconds;
    }

    public double Speed { get; }

    public double Acceleration { get; }

    public double Length { get; }

    public double RampSeconds { get; }

    public double RampLength { get; }

    public double DurationSeconds { get; }

    /// <summary>Distance along the polyline of vertex <paramref name="index"/>.</summary>
    public double LengthAt(int index) => _s[index];

    /// <summary>How many vertices the polyline has (run-up start and run-out end included).</summary>
    public int VertexCount => _s.Length;

    /// <summary>Vertex <paramref name="index"/>, microsteps.</summary>
    public (double X, double Y) Vertex(int index) => (_x[index], _y[index]);

    /// <summary>The segment that holds a distance along the polyline: the last vertex at or before it (0..VertexCount - 2).</summary>
    public int SegmentAt(double distance)
    {
        var i = Array.BinarySearch(_s, distance);
        i = i >= 0 ? i : ~i - 1;
        return Math.Clamp(i, 0, Math.Max(0, _s.Length - 2));
    }

    /// <summary>
    /// Whether segment <paramref name="segment"/> is among those <see cref="DistanceToPath"/> measures for a window: from the
    /// last vertex before <paramref name="from"/> on, each segment starting at or before <paramref name="to"/>.
    /// </summary>
    public bool InWindow(int segment, double from, double to) =>
        segment >= 0 && segment < _s.Length - 1 && _s[segment + 1] >= from && _s[segment] <= to;

    /// <summary>Distance along the polyline at a time.</summary>
    public double DistanceAt(double seconds)
    {
        if (seconds <= 0)
        {
            return 0;
        }

        if (seconds >= DurationSeconds)
        {
            return Length;
        }

        if (seconds < RampSeconds)
        {
            return 0.5 * Acceleration * seconds * seconds;
        }

        var left = DurationSeconds - seconds;
        return left < RampSeconds ? Length - (0.5 * Acceleration * left * left) : RampLength + (Speed * (seconds - RampSeconds));
    }

    /// <summary>The time the motion passes a distance along the polyline (in the constant-speed part).</summary>
    public double TimeAtDistance(double distance) => RampSeconds + ((distance - RampLength) / Speed);

    public (double X, double Y) PositionAt(double seconds) => PointAt(DistanceAt(seconds));

    public (double X, double Y) PointAt(double distance)
    {
        var i = Array.BinarySearch(_s, distance);
        if (i >= 0)
        {
            return (_x[i], _y[i]);
        }

        i = ~i;
        if (i <= 0)
        {
            return (_x[0], _y[0]);
        }

        if (i >= _s.Length)
        {
            return (_x[^1], _y[^1]);
        }

        var f = (distance - _s[i - 1]) / (_s[i] - _s[i - 1]);
        return (_x[i - 1] + (f * (_x[i] - _x[i - 1])), _y[i - 1] + (f * (_y[i] - _y[i - 1])));
    }

    /// <summary>Distance from a point to the polyline's segments that lie between two distances along it.</summary>
    public double DistanceToPath(double x, double y, double from, double to)
    {
        var found = Array.BinarySearch(_s, from);
        var first = Math.Max(0, (found >= 0 ? found : ~found) - 1);
        var best = double.PositiveInfinity;
        for (var i = first; i < _s.Length - 1 && _s[i] <= to; i++)
        {
            best = Math.Min(best, SegmentDistance(x, y, _x[i], _y[i], _x[i + 1], _y[i + 1]));
        }

        return best;
    }

    /// <summary>The segment of a window (as <see cref="DistanceToPath"/> takes it) nearest to a point, -1 when the window is empty.</summary>
    public int NearestSegment(double x, double y, double from, double to)
    {
        var found = Array.BinarySearch(_s, from);
        var first = Math.Max(0, (found >= 0 ? found : ~found) - 1);
        var (best, nearest) = (double.PositiveInfinity, -1);
        for (var i = first; i < _s.Length - 1 && _s[i] <= to; i++)
        {
            var d = SegmentDistance(x, y, _x[i], _y[i], _x[i + 1], _y[i + 1]);
            if (d < best)
            {
                (best, nearest) = (d, i);
            }
        }

        return nearest;
    }

    // For DistanceFollowing, how many segments share one bound.
    private const int Block = 8;

    // For DistanceFollowing: each segment's key, its distance when last measured plus how far the point had moved by then
    // (the point is at least key - moved away from it now); the smallest key of each block of segments; the point's moves.
    private double[]? _keys;
    private double[]? _blockKeys;
    private double _moved;
    private (double X, double Y)? _last;
    private int _first;
    private int _middle;

    /// <summary>
    /// <see cref="DistanceToPath"/> for one point followed in small steps (the model of a stroke, every 0.25 ms): the same
    /// value, without measuring every segment of the window at every step. A segment d away when the point had moved m is
    /// at least d - (moved since m) away now, so it is measured again only once that bound could beat the nearest so far,
    /// and a block of segments is passed over at once while its smallest bound cannot. A stroke of 500 000 vertices has
    /// hundreds of tiny segments in its window, and measuring each at every step was most of its planning.
    /// </summary>
    public double DistanceFollowing(double x, double y, double from, double to)
    {
        var segments = _s.Length - 1;
        if (segments <= 0)
        {
            return DistanceToPath(x, y, from, to);
        }

        if (_keys is null || _blockKeys is null)
        {
            // Never measured: a key that no bound passes over.
            _keys = new double[segments];
            _blockKeys = new double[((segments - 1) / Block) + 1];
            Array.Fill(_keys, double.NegativeInfinity);
            Array.Fill(_blockKeys, double.NegativeInfinity);
        }

        if (_last is { } last)
        {
            // Rounded up a little each step, so the sum never falls short of the true path the point took.
            var step = Math.Sqrt(Sq(x - last.X) + Sq(y - last.Y));
            _moved += step + (1e-15 * (_moved + step)) + 1e-12;
        }

        _last = (x, y);

        // The window's first segment, the last before from (as DistanceToPath finds it): the window only moves forward.
        _first = Before(from, _first);
        var first = _first;
        if (first >= segments || _s[first] > to)
        {
            return double.PositiveInfinity;
        }

        // A first nearest, the segment where the ideal point is (mid-window), lets the others be passed over from the start.
        _middle = Before((from + to) / 2, Math.Max(_middle, first));
        var near = Math.Min(_middle, segments - 1);
        near = _s[near] <= to ? near : first;
        var best = Measure(near, x, y);

        // Everything under this is measured: what rounding in the keys could hide, far below a microstep.
        var threshold = best + 1e-9 + (1e-15 * _moved) + _moved;
        for (var block = first / Block; block * Block < segments && _s[block * Block] <= to; block++)
        {
            if (_blockKeys[block] > threshold)
            {
                continue;
            }

            var start = block * Block;
            var end = Math.Min(start + Block, segments);
            for (var i = Math.Max(start, first); i < end && _s[i] <= to; i++)
            {
                if (_keys[i] <= threshold)
                {
                    best = Math.Min(best, Measure(i, x, y));
                    threshold = best + 1e-9 + (1e-15 * _moved) + _moved;
                }
            }

            var smallest = double.PositiveInfinity;
            for (var i = start; i < end; i++)
            {
                smallest = Math.Min(smallest, _keys[i]);
            }

            _blockKeys[block] = smallest;
        }

        return best;
    }

    /// <summary>The last vertex before <paramref name="distance"/> along the polyline (0 when none), looked for from <paramref name="from"/> on.</summary>
    private int Before(double distance, int from)
    {
        if (from > 0 && _s[from] >= distance)
        {
            // Back: never while a stroke is followed, found by bisection all the same.
            var found = Array.BinarySearch(_s, distance);
            return Math.Max(0, (found >= 0 ? found : ~found) - 1);
        }

        var i = from;
        while (i + 1 < _s.Length && _s[i + 1] < distance)
        {
            i++;
        }

        return i;
    }

    private double Measure(int segment, double x, double y)
    {
        var d = SegmentDistance(x, y, _x[segment], _y[segment], _x[segment + 1], _y[segment + 1]);
        _keys![segment] = d + _moved;
        return d;
    }

    public static double SegmentDistance(double px, double py, double ax, double ay, double bx, double by)
    {
        double dx = bx - ax, dy = by - ay;
        var l2 = (dx * dx) + (dy * dy);
        var t = l2 == 0 ? 0 : Math.Clamp((((px - ax) * dx) + ((py - ay) * dy)) / l2, 0, 1);
        return Math.Sqrt(Sq(px - (ax + (t * dx))) + Sq(py - (ay + (t * dy))));
    }

    private static double Sq(double v) => v * v;
}
