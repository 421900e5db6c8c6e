using System.Buffers.Binary;

namespace LaserEngrave.Core.Imaging;

/// <summary>Writes a mask as a 1-bit BMP: palette entry 0 black (burn), entry 1 white, the format the CEILAP tool read.</summary>
public static class BmpMaskWriter
{
    private const int HeaderBytes = 14 + 40 + 8;

    /// <summary>Writes <paramref name="mask"/>; with <paramref name="pitchUm"/> the file states the matching resolution.</summary>
    public static void Write(Stream output, BitMask mask, double? pitchUm = null)
    {
        ArgumentNullException.ThrowIfNull(output);
        ArgumentNullException.ThrowIfNull(mask);
        var stride = ((mask.Width + 31) / 32) * 4;
        var imageBytes = (long)stride * mask.Height;
        if (HeaderBytes + imageBytes > int.MaxValue)
        {
            throw new ArgumentOutOfRangeException(nameof(mask), $"a {mask.Width} x {mask.Height} mask is too large for a BMP file");
        }

        var pixelsPerMetre = pitchUm is { } p && p > 0 ? (int)Math.Round(1e6 / p) : 0;
        var header = new byte[HeaderBytes];
        header[0] = (byte)'B';
        header[1] = (byte)'M';
        BinaryPrimitives.WriteInt32LittleEndian(header.AsSpan(2), (int)(HeaderBytes + imageBytes));
        BinaryPrimitives.WriteInt32LittleEndian(header.AsSpan(10), HeaderBytes);
        BinaryPrimitives.WriteInt32LittleEndian(header.AsSpan(14), 40);
        BinaryPrimitives.WriteInt32LittleEndian(header.AsSpan(18), mask.Width);
        BinaryPrimitives.WriteInt32LittleEndian(header.AsSpan(22), mask.Height);
        BinaryPrimitives.WriteInt16LittleEndian(header.AsSpan(26), 1);
        BinaryPrimitives.WriteInt16LittleEndian(header.AsSpan(28), 1);
        BinaryPrimitives.WriteInt32LittleEndian(header.AsSpan(34), (int)imageBytes);
        BinaryPrimitives.WriteInt32LittleEndian(header.AsSpan(38), pixelsPerMetre);
        BinaryPrimitives.WriteInt32LittleEndian(header.AsSpan(42), pixelsPerMetre);
        BinaryPrimitives.WriteInt32LittleEndian(header.AsSpan(46), 2);
        BinaryPrimitives.WriteInt32LittleEndian(header.AsSpan(50), 2);

        // Palette: 0 = black (burn), 1 = white; bytes are blue, green, red, reserved.
        header[58] = header[59] = header[60] = 255;
        output.Write(header);

        var row = new byte[stride];
        for (var y = mask.Height - 1; y >= 0; y--)
        {
            Array.Fill(row, (byte)0);
            for (var x = 0; x < mask.Width; x++)
            {
                if (!mask[x, y])
                {
                    row[x >> 3] |= (byte)(0x80 >> (x & 7));
                }
            }

            output.Write(row);
        }
    }

    public static void Write(string path, BitMask mask, double? pitchUm = null)
    {
        using var stream = File.Create(path);
        Write(stream, mask, pitchUm);
    }
}
