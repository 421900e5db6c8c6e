namespace LaserEngrave.Core.Alignment;

/// <summary>A rotation then a translation, from job coordinates to true sample coordinates, mm: p = R(angle) j + (tx, ty).</summary>
/// <remarks>The angle turns +x towards +y (with y down the image, clockwise as seen on screen).</remarks>
public readonly record struct RigidTransform(double AngleRadians, double TranslationXMm, double TranslationYMm)
{
    public double AngleDegrees => AngleRadians * 180 / Math.PI;

    public (double X, double Y) Apply(double x, double y)
    {
        var (s, c) = Math.SinCos(AngleRadians);
        return ((c * x) - (s * y) + TranslationXMm, (s * x) + (c * y) + TranslationYMm);
    }

    public (double X, double Y) Invert(double x, double y)
    {
        var (s, c) = Math.SinCos(AngleRadians);
        double dx = x - TranslationXMm, dy = y - TranslationYMm;
        return ((c * dx) + (s * dy), (-s * dx) + (c * dy));
    }
}
