namespace LaserEngrave.Core.Imaging;

/// <summary>Ordered dithering with the 8 x 8 Bayer matrix: a pixel burns when its luminance is below the matrix level at its place.</summary>
internal sealed class BayerDitherer : Ditherer
{
    /// <summary>Thresholds (m + 0.5) / 64 for m = 0..63 in Bayer order; a 50 % grey burns exactly 32 of every 64 pixels.</summary>
    private static readonly float[] Levels = BuildLevels();

    public override void DitherRow(int y, ReadOnlySpan<float> luminance, ReadOnlySpan<bool> transparent, Span<ulong> maskRow)
    {
        var row = Levels.AsSpan((y & 7) * 8, 8);
        for (var x = 0; x < luminance.Length; x++)
        {
            if (!transparent[x] && luminance[x] < row[x & 7])
            {
                maskRow[x >> 6] |= 1UL << (x & 63);
            }
        }
    }

    /// <summary>The Bayer index of (x, y) in an 8 x 8 matrix: interleave the bits of x ^ y and y, lowest bits most significant.</summary>
    internal static int Index(int x, int y)
    {
        var v = 0;
        var xy = x ^ y;
        for (var bit = 0; bit < 3; bit++)
        {
            v = (v << 2) | (((xy >> bit) & 1) << 1) | ((y >> bit) & 1);
        }

        return v;
    }

    private static float[] BuildLevels()
    {
        var levels = new float[64];
        for (var y = 0; y < 8; y++)
        {
            for (var x = 0; x < 8; x++)
            {
                levels[(y * 8) + x] = (Index(x, y) + 0.5f) / 64f;
            }
        }

        return levels;
    }
}
