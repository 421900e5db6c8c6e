namespace LaserEngrave.Core.Imaging;

/// <summary>Reads and writes packed palette indices (leftmost pixel in the most significant bits, as BMP and PNG store them).</summary>
internal static class IndexedPixels
{
    public static int Get(ReadOnlySpan<byte> row, int x, int bits) => bits switch
    {
        8 => row[x],
        4 => (row[x >> 1] >> ((1 - (x & 1)) << 2)) & 0xF,
        2 => (row[x >> 2] >> ((3 - (x & 3)) << 1)) & 0x3,
        1 => (row[x >> 3] >> (7 - (x & 7))) & 0x1,
        _ => throw new ArgumentOutOfRangeException(nameof(bits)),
    };

    public static void Set(Span<byte> row, int x, int bits, int value)
    {
        switch (bits)
        {
            case 8:
                row[x] = (byte)value;
                break;
            case 4:
                var shift4 = (1 - (x & 1)) << 2;
                row[x >> 1] = (byte)((row[x >> 1] & ~(0xF << shift4)) | ((value & 0xF) << shift4));
                break;
            case 2:
                var shift2 = (3 - (x & 3)) << 1;
                row[x >> 2] = (byte)((row[x >> 2] & ~(0x3 << shift2)) | ((value & 0x3) << shift2));
                break;
            case 1:
                var shift1 = 7 - (x & 7);
                row[x >> 3] = (byte)((row[x >> 3] & ~(1 << shift1)) | ((value & 1) << shift1));
                break;
            default:
                throw new ArgumentOutOfRangeException(nameof(bits));
        }
    }

    /// <summary>Zeroes the bits past the last pixel of a packed row, so stray bits in a file never read as pixels.</summary>
    public static void ClearPadding(Span<byte> row, int width, int bits)
    {
        var usedBits = (width * bits) & 7;
        if (usedBits != 0)
        {
            row[(width * bits) >> 3] &= (byte)(0xFF << (8 - usedBits));
        }
    }

    /// <summary>The first pixel whose index is not below <paramref name="paletteCount"/>, or -1.</summary>
    public static int FindIndexOutside(ReadOnlySpan<byte> row, int width, int bits, int paletteCount)
    {
        if (paletteCount >= 1 << bits)
        {
            return -1;
        }

        if (bits == 8)
        {
            return row[..width].IndexOfAnyInRange((byte)paletteCount, byte.MaxValue);
        }

        for (var x = 0; x < width; x++)
        {
            if (Get(row, x, bits) >= paletteCount)
            {
                return x;
            }
        }

        return -1;
    }
}
