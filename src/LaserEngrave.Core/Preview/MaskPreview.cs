using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Preview;

/// <summary>Renders a mask as it will be burned, black on white, scaled by nearest neighbour so edges stay sharp.</summary>
public static class MaskPreview
{
    /// <summary>Largest side accepted, pixels (a greyscale buffer of 64 MB).</summary>
    public const int MaxSidePx = 8192;

    /// <summary>Writes a PNG whose longer side is <paramref name="maxSidePx"/>, aspect kept.</summary>
    public static void Render(BitMask mask, Stream output, int maxSidePx)
    {
        ArgumentNullException.ThrowIfNull(mask);
        var size = PreviewSize.Fit(mask.Width, mask.Height, maxSidePx);
        Render(mask, output, size.Width, size.Height);
    }

    /// <summary>Writes a PNG of exactly <paramref name="widthPx"/> x <paramref name="heightPx"/>.</summary>
    public static void Render(BitMask mask, Stream output, int widthPx, int heightPx)
    {
        ArgumentNullException.ThrowIfNull(output);
        PngWriter.WriteGray(output, widthPx, heightPx, RenderGray(mask, widthPx, heightPx));
    }

    /// <summary>Writes the preview to the file at <paramref name="path"/>.</summary>
    public static void Render(BitMask mask, string path, int maxSidePx)
    {
        using var file = File.Create(path);
        Render(mask, file, maxSidePx);
    }

    /// <summary>The preview's pixels: one byte per pixel, 0 = burn, 255 = no burn, rows top to bottom.</summary>
    public static byte[] RenderGray(BitMask mask, int widthPx, int heightPx)
    {
        ArgumentNullException.ThrowIfNull(mask);
        ArgumentOutOfRangeException.ThrowIfLessThan(widthPx, 1);
        ArgumentOutOfRangeException.ThrowIfLessThan(heightPx, 1);
        ArgumentOutOfRangeException.ThrowIfGreaterThan(widthPx, MaxSidePx);
        ArgumentOutOfRangeException.ThrowIfGreaterThan(heightPx, MaxSidePx);

        // Each preview pixel shows the mask pixel under its centre.
        var sourceX = new int[widthPx];
        for (var x = 0; x < widthPx; x++)
        {
            sourceX[x] = (int)((((2L * x) + 1) * mask.Width) / (2L * widthPx));
        }

        var gray = new byte[widthPx * heightPx];
        for (var y = 0; y < heightPx; y++)
        {
            var words = mask.ReadRow((int)((((2L * y) + 1) * mask.Height) / (2L * heightPx)));
            var row = gray.AsSpan(y * widthPx, widthPx);
            for (var x = 0; x < widthPx; x++)
            {
                var sx = sourceX[x];
                row[x] = (words[sx >> 6] >> (sx & 63) & 1) != 0 ? (byte)0 : (byte)255;
            }
        }

        return gray;
    }
}
