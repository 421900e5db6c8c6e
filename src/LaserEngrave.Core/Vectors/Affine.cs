namespace LaserEngrave.Core.Vectors;

/// <summary>A 2D affine transform x' = A x + C y + E, y' = B x + D y + F (SVG's matrix(a b c d e f)).</summary>
public readonly record struct Affine(double A, double B, double C, double D, double E, double F)
{
    public static Affine Identity { get; } = new(1, 0, 0, 1, 0, 0);

    public static Affine Translate(double x, double y) => new(1, 0, 0, 1, x, y);

    public static Affine Scale(double x, double y) => new(x, 0, 0, y, 0, 0);

    /// <summary>A rotation by <paramref name="degrees"/>, counter-clockwise when y grows up (clockwise on screen when y grows down).</summary>
    public static Affine Rotate(double degrees)
    {
        var r = degrees * Math.PI / 180;
        double cos = Math.Cos(r), sin = Math.Sin(r);

        // Exact for the right angles CAD drawings use most, so rotated vertices stay where they were drawn.
        if (degrees % 90 == 0)
        {
            cos = Math.Round(cos);
            sin = Math.Round(sin);
        }

        return new(cos, sin, -sin, cos, 0, 0);
    }

    public static Affine SkewX(double degrees) => new(1, 0, Math.Tan(degrees * Math.PI / 180), 1, 0, 0);

    public static Affine SkewY(double degrees) => new(1, Math.Tan(degrees * Math.PI / 180), 0, 1, 0, 0);

    public bool IsIdentity => this == Identity;

    /// <summary>The transform that applies <paramref name="first"/>, then <paramref name="then"/>.</summary>
    public static Affine Compose(Affine first, Affine then) => new(
        (then.A * first.A) + (then.C * first.B),
        (then.B * first.A) + (then.D * first.B),
        (then.A * first.C) + (then.C * first.D),
        (then.B * first.C) + (then.D * first.D),
        (then.A * first.E) + (then.C * first.F) + then.E,
        (then.B * first.E) + (then.D * first.F) + then.F);

    public DrawingPoint Apply(DrawingPoint p) => IsIdentity ? p : new((A * p.X) + (C * p.Y) + E, (B * p.X) + (D * p.Y) + F);

    /// <summary>Transforms a direction (no translation).</summary>
    public DrawingPoint ApplyVector(DrawingPoint v) => new((A * v.X) + (C * v.Y), (B * v.X) + (D * v.Y));

    public double Determinant => (A * D) - (B * C);
}
