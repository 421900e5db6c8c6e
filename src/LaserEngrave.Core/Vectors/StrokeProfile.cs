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

    public static double SegmentDistance(double px, double py, double ax, double ay, double bx, double by)
    {
        double dx = bx - ax, dy = by - ay;
        var l2 = (dx * dx) + (dy * dy);
        var t = l2 == 0 ? 0 : Math.Clamp((((px - ax) * dx) + ((py - ay) * dy)) / l2, 0, 1);
        return Math.Sqrt(Sq(px - (ax + (t * dx))) + Sq(py - (ay + (t * dy))));
    }

    private static double Sq(double v) => v * v;
}
