namespace LaserEngrave.Core.Vectors;

/// <summary>A non-uniform rational B-spline (DXF SPLINE), evaluated with de Boor's algorithm on homogeneous points.</summary>
public sealed class NurbsCurve : IDrawingCurve
{
    private const int MaxDepth = 24;

    private readonly DrawingPoint[] _points;
    private readonly double[] _weights;
    private readonly double[] _knots;

    /// <param name="degree">Degree p (1..10).</param>
    /// <param name="knots">n + p + 1 non-decreasing knots for n control points.</param>
    /// <param name="points">The n control points.</param>
    /// <param name="weights">n positive weights, or null for a non-rational spline.</param>
    public NurbsCurve(int degree, double[] knots, DrawingPoint[] points, double[]? weights = null)
    {
        ArgumentNullException.ThrowIfNull(knots);
        ArgumentNullException.ThrowIfNull(points);
        if (degree is < 1 or > 10)
        {
            throw new ArgumentException($"degree {degree} is not 1..10", nameof(degree));
        }

        if (points.Length < degree + 1)
        {
            throw new ArgumentException($"{points.Length} control points are too few for degree {degree} (at least {degree + 1})", nameof(points));
        }

        if (knots.Length != points.Length + degree + 1)
        {
            throw new ArgumentException($"{knots.Length} knots for {points.Length} control points of degree {degree}: expected {points.Length + degree + 1}", nameof(knots));
        }

        for (var i = 1; i < knots.Length; i++)
        {
            if (!(knots[i] >= knots[i - 1]) || !double.IsFinite(knots[i]))
            {
                throw new ArgumentException($"knot {i} ({knots[i]}) is below the one before it ({knots[i - 1]})", nameof(knots));
            }
        }

        if (!(knots[points.Length] > knots[degree]))
        {
            throw new ArgumentException("the knots leave the spline an empty domain", nameof(knots));
        }

        if (weights is not null && (weights.Length != points.Length || weights.Any(w => !(w > 0) || !double.IsFinite(w))))
        {
            throw new ArgumentException($"{points.Length} control points need {points.Length} weights above 0", nameof(weights));
        }

        Degree = degree;
        _knots = knots;
        _points = points;
        _weights = weights ?? [.. Enumerable.Repeat(1.0, points.Length)];
        Start = At(Domain.Start);
        End = At(Domain.End);
    }

    public int Degree { get; }

    public IReadOnlyList<DrawingPoint> Points => _points;

    public DrawingPoint Start { get; }

    public DrawingPoint End { get; }

    /// <summary>The parameter range the curve is defined on: knot p to knot n.</summary>
    public (double Start, double End) Domain => (_knots[Degree], _knots[_points.Length]);

    public IDrawingCurve Transform(Affine transform) =>
        new NurbsCurve(Degree, _knots, [.. _points.Select(transform.Apply)], _weights);

    /// <summary>The point at parameter <paramref name="u"/> (clamped to the domain).</summary>
    public DrawingPoint At(double u)
    {
        var p = Degree;
        u = Math.Clamp(u, Domain.Start, Domain.End);

        // The span k with knot[k] <= u < knot[k + 1], the last non-empty one at the domain's end.
        var k = p;
        while (k < _points.Length - 1 && u >= _knots[k + 1])
        {
            k++;
        }

        Span<double> x = stackalloc double[p + 1];
        Span<double> y = stackalloc double[p + 1];
        Span<double> w = stackalloc double[p + 1];
        for (var j = 0; j <= p; j++)
        {
            var i = j + k - p;
            w[j] = _weights[i];
            x[j] = _points[i].X * w[j];
            y[j] = _points[i].Y * w[j];
        }

        for (var r = 1; r <= p; r++)
        {
            for (var j = p; j >= r; j--)
            {
                var i = j + k - p;
                var denominator = _knots[i + p - r + 1] - _knots[i];
                var alpha = denominator == 0 ? 0 : (u - _knots[i]) / denominator;
                x[j] = ((1 - alpha) * x[j - 1]) + (alpha * x[j]);
                y[j] = ((1 - alpha) * y[j - 1]) + (alpha * y[j]);
                w[j] = ((1 - alpha) * w[j - 1]) + (alpha * w[j]);
            }
        }

        return new DrawingPoint(x[p] / w[p], y[p] / w[p]);
    }

    /// <summary>Each knot span in four pieces, each halved until its quarter, middle and three-quarter points lie within the tolerance of its chord.</summary>
    public void Flatten(double tolerance, List<DrawingPoint> output)
    {
        for (var k = Degree; k < _points.Length; k++)
        {
            double a = _knots[k], b = _knots[k + 1];
            if (!(b > a))
            {
                continue;
            }

            for (var i = 0; i < 4; i++)
            {
                var u0 = a + ((b - a) * i / 4);
                var u1 = i == 3 ? b : a + ((b - a) * (i + 1) / 4);
                Subdivide(u0, At(u0), u1, At(u1), tolerance, output, 0);
            }
        }

        output[^1] = End;
    }

    private void Subdivide(double u0, DrawingPoint p0, double u1, DrawingPoint p1, double tolerance, List<DrawingPoint> output, int depth)
    {
        var um = (u0 + u1) / 2;
        var pm = At(um);
        if (depth < MaxDepth
            && (DrawingPoint.DistanceToSegment(pm, p0, p1) > tolerance
                || DrawingPoint.DistanceToSegment(At((u0 + um) / 2), p0, p1) > tolerance
                || DrawingPoint.DistanceToSegment(At((um + u1) / 2), p0, p1) > tolerance))
        {
            Subdivide(u0, p0, um, pm, tolerance, output, depth + 1);
            Subdivide(um, pm, u1, p1, tolerance, output, depth + 1);
            return;
        }

        output.Add(p1);
    }
}
