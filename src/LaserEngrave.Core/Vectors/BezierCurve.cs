namespace LaserEngrave.Core.Vectors;

/// <summary>A quadratic (3 points) or cubic (4 points) Bézier curve.</summary>
public sealed class BezierCurve : IDrawingCurve
{
    private readonly DrawingPoint[] _points;

    public BezierCurve(params DrawingPoint[] points)
    {
        if (points.Length is < 3 or > 4)
        {
            throw new ArgumentException("a Bézier curve has 3 or 4 control points", nameof(points));
        }

        _points = points;
    }

    public IReadOnlyList<DrawingPoint> Points => _points;

    public DrawingPoint Start => _points[0];

    public DrawingPoint End => _points[^1];

    public IDrawingCurve Transform(Affine transform) => new BezierCurve([.. _points.Select(transform.Apply)]);

    public DrawingPoint At(double t)
    {
        var s = 1 - t;
        return _points.Length == 3
            ? (_points[0] * (s * s)) + (_points[1] * (2 * s * t)) + (_points[2] * (t * t))
            : (_points[0] * (s * s * s)) + (_points[1] * (3 * s * s * t)) + (_points[2] * (3 * s * t * t)) + (_points[3] * (t * t * t));
    }

    /// <summary>Equal steps of t: with |P''| at most M = n (n - 1) max |second difference of the points|, a step h bows at most M h² / 8.</summary>
    public void Flatten(double tolerance, List<DrawingPoint> output)
    {
        var degree = _points.Length - 1;
        var largest = 0.0;
        for (var i = 0; i + 2 < _points.Length; i++)
        {
            largest = Math.Max(largest, (_points[i] - (_points[i + 1] * 2) + _points[i + 2]).Length);
        }

        var m = degree * (degree - 1) * largest;
        var n = (int)Math.Min(1_000_000, Math.Max(1, Math.Ceiling(Math.Sqrt(m / (8 * tolerance)))));
        for (var i = 1; i < n; i++)
        {
            output.Add(At(i / (double)n));
        }

        output.Add(End);
    }
}
