namespace LaserEngrave.Core.Preview;

/// <summary>The pixel size of a preview.</summary>
public readonly record struct PreviewSize(int Width, int Height)
{
    /// <summary>The largest size with the aspect of <paramref name="width"/> x <paramref name="height"/> whose longer side is <paramref name="maxSidePx"/> (scaling up or down; at least 1 x 1).</summary>
    public static PreviewSize Fit(double width, double height, int maxSidePx)
    {
        ArgumentOutOfRangeException.ThrowIfLessThan(maxSidePx, 1);
        if (!(width > 0) || !(height > 0))
        {
            throw new ArgumentOutOfRangeException(nameof(width), $"{width} x {height} has no area");
        }

        var scale = maxSidePx / Math.Max(width, height);
        return new PreviewSize(
            (int)Math.Clamp(Math.Round(width * scale), 1, maxSidePx),
            (int)Math.Clamp(Math.Round(height * scale), 1, maxSidePx));
    }
}
