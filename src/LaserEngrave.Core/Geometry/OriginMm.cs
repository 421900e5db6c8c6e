namespace LaserEngrave.Core.Geometry;

/// <summary>Where the image's top-left corner sits on the stage, in mm from the stage's zero on each axis.</summary>
/// <param name="X">Stage X of the image's left edge, mm.</param>
/// <param name="Y">Stage Y of the image's top edge, mm (y grows down the image).</param>
public readonly record struct OriginMm(double X, double Y)
{
    /// <summary>The stage's zero: the image's top-left corner at (0, 0).</summary>
    public static OriginMm Zero => default;
}
