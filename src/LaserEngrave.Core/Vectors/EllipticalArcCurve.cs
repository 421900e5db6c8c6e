namespace LaserEngrave.Core.Vectors;

/// <summary>An arc of an ellipse, P(t) = Center + U cos t + V sin t for t from T0 to T0 + Sweep: circles, arcs, ellipses, bulges and SVG arcs.</summary>
/// <remarks>
/// The form survives any affine transform (Center, U and V transform; t does not), so a circle scaled unevenly or
/// skewed stays exact. Start and End are kept as given, so an arc between two polyline vertices ends on them exactly.
/// </remarks>
public sealed class EllipticalArcCurve : IDrawingCurve
{
    public EllipticalArcCurve(DrawingPoint center, DrawingPoint u, DrawingPoint v, double t0, double sweep, DrawingPoint? start = null, DrawingPoint? end = null)
    {
        Center = center;
        U = u;
        V = v;
        T0 = t0;
        Sweep = sweep;
        Start = start ?? At(t0);
        End = end ?? (Math.Abs(sweep) >= 2 * Math.PI ? Start : At(t0 + sweep));
    }

    public DrawingPoint Center { get; }

    public DrawingPoint U { get; }

    public DrawingPoint V { get; }

    public double T0 { get; }

    public double Sweep { get; }

    public DrawingPoint Start { get; }

    public DrawingPoint End { get; }

    /// <summary>A circular arc from <paramref name="startDegrees"/> turning by <paramref name="sweepDegrees"/> (positive = from +x towards +y).</summary>
    public static EllipticalArcCurve Circular(DrawingPoint center, double radius, double startDegrees, double sweepDegrees) =>
        new(center, new DrawingPoint(radius, 0), new DrawingPoint(0, radius), startDegrees * Math.PI / 180, sweepDegrees * Math.PI / 180);

    public DrawingPoint At(double t) => Center + (U * Math.Cos(t)) + (V * Math.Sin(t));

    public IDrawingCurve Transform(Affine transform) => new EllipticalArcCurve(
        transform.Apply(Center), transform.ApplyVector(U), transform.ApplyVector(V), T0, Sweep, transform.Apply(Start), transform.Apply(End));

    /// <summary>Equal steps of t, as many as keep the chord within the tolerance where the arc is most curved.</summary>
    /// <remarks>
    /// |P''| is at most the largest singular value r of [U V]; a step h then bows at most r (1 - cos(h/2)) from its
    /// chord, exactly so on a circle of radius r, whose polyline is then shorter than the arc by about tolerance / (3 r).
    /// </remarks>
    public void Flatten(double tolerance, List<DrawingPoint> output)
    {
        double a = DrawingPoint.Dot(U, U), b = DrawingPoint.Dot(U, V), d = DrawingPoint.Dot(V, V);
        var r = Math.Sqrt(((a + d) / 2) + Math.Sqrt((((a - d) / 2) * ((a - d) / 2)) + (b * b)));
        var step = tolerance >= r ? Math.PI / 2 : 2 * Math.Acos(1 - (tolerance / r));
        var n = (int)Math.Min(1_000_000, Math.Max(1, Math.Ceiling(Math.Abs(Sweep) / step)));
        for (var i = 1; i < n; i++)
        {
            output.Add(At(T0 + (Sweep * i / n)));
        }

        output.Add(End);
    }
}
