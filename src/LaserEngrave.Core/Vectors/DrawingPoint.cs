namespace LaserEngrave.Core.Vectors;

/// <summary>A point of a drawing, in the drawing's coordinates (millimetres once read, y down) or in microsteps once placed.</summary>
public readonly record struct DrawingPoint(double X, double Y)
{
    public static DrawingPoint operator +(DrawingPoint a, DrawingPoint b) => new(a.X + b.X, a.Y + b.Y);

    public static DrawingPoint operator -(DrawingPoint a, DrawingPoint b) => new(a.X - b.X, a.Y - b.Y);

    public static DrawingPoint operator *(DrawingPoint a, double k) => new(a.X * k, a.Y * k);

    public double Length => Math.Sqrt((X * X) + (Y * Y));

    public static double Distance(DrawingPoint a, DrawingPoint b) => (a - b).Length;

    public static double Dot(DrawingPoint a, DrawingPoint b) => (a.X * b.X) + (a.Y * b.Y);

    /// <summary>Distance of <paramref name="p"/> from the segment <paramref name="a"/>-<paramref name="b"/>.</summary>
    public static double DistanceToSegment(DrawingPoint p, DrawingPoint a, DrawingPoint b)
    {
        var ab = b - a;
        var lengthSquared = Dot(ab, ab);
        if (lengthSquared == 0)
        {
            return Distance(p, a);
        }

        var t = Math.Clamp(Dot(p - a, ab) / lengthSquared, 0, 1);
        return Distance(p, a + (ab * t));
    }
}
