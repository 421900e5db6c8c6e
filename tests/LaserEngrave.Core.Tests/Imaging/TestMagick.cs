using System.Buffers.Binary;
using ImageMagick;

namespace LaserEngrave.Core.Tests.Imaging;

/// <summary>Writes JPEG, TIFF and WebP test images with ImageMagick, and patches their headers to lie.</summary>
internal static class TestMagick
{
    public const int Width = 64;
    public const int Height = 32;

    /// <summary>The black rectangle of <see cref="BlackOnWhite"/>: columns 16..47, rows 8..23.</summary>
    public static bool InRectangle(int x, int y) => x is >= 16 and < 48 && y is >= 8 and < 24;

    /// <summary>A white <see cref="Width"/> x <see cref="Height"/> image with a black rectangle, encoded as <paramref name="format"/>.</summary>
    public static byte[] BlackOnWhite(MagickFormat format, Action<MagickImage>? configure = null) =>
        Encode(Draw((x, y) => InRectangle(x, y) ? (byte)0 : (byte)255), format, configure);

    /// <summary>An image whose pixel (x, y) has the grey level <paramref name="grey"/> gives, encoded as <paramref name="format"/>.</summary>
    public static byte[] Grey(Func<int, int, byte> grey, MagickFormat format, Action<MagickImage>? configure = null) =>
        Encode(Draw(grey), format, configure);

    /// <summary>Several pages, the first black, the others white.</summary>
    public static byte[] Pages(int count, MagickFormat format)
    {
        using var pages = new MagickImageCollection();
        for (var i = 0; i < count; i++)
        {
            pages.Add(new MagickImage(i == 0 ? MagickColors.Black : MagickColors.White, 8, 8));
        }

        return pages.ToByteArray(format);
    }

    public static MagickImage Draw(Func<int, int, byte> grey, int width = Width, int height = Height) =>
        Draw((x, y) => grey(x, y) is var v ? (v, v, v) : default, width, height);

    /// <summary>An opaque image whose pixel (x, y) has the colour <paramref name="colour"/> gives.</summary>
    public static MagickImage Draw(Func<int, int, (byte R, byte G, byte B)> colour, int width = Width, int height = Height)
    {
        var image = new MagickImage(MagickColors.White, (uint)width, (uint)height);
        var rgb = new byte[width * height * 3];
        for (var y = 0; y < height; y++)
        {
            for (var x = 0; x < width; x++)
            {
                var (r, g, b) = colour(x, y);
                var o = ((y * width) + x) * 3;
                (rgb[o], rgb[o + 1], rgb[o + 2]) = (r, g, b);
            }
        }

        using var pixels = image.GetPixels();
        pixels.SetArea(0, 0, (uint)width, (uint)height, rgb);
        return image;
    }

    public static byte[] Encode(MagickImage image, MagickFormat format, Action<MagickImage>? configure = null)
    {
        using (image)
        {
            configure?.Invoke(image);
            return image.ToByteArray(format);
        }
    }

    /// <summary>Rewrites the first JPEG frame header (SOF0/SOF2) to claim <paramref name="width"/> x <paramref name="height"/>.</summary>
    public static byte[] WithJpegSize(byte[] jpeg, ushort width, ushort height)
    {
        var patched = (byte[])jpeg.Clone();
        for (var i = 2; i + 9 < patched.Length; i++)
        {
            if (patched[i] == 0xFF && patched[i + 1] is 0xC0 or 0xC2)
            {
                BinaryPrimitives.WriteUInt16BigEndian(patched.AsSpan(i + 5), height);
                BinaryPrimitives.WriteUInt16BigEndian(patched.AsSpan(i + 7), width);
                return patched;
            }
        }

        throw new InvalidOperationException("no SOF0 or SOF2 marker in the JPEG");
    }

    /// <summary>Rewrites the first IFD of a little-endian TIFF to claim <paramref name="width"/> x <paramref name="height"/> (tags 256, 257 as LONG), and optionally its rows per strip (278).</summary>
    public static byte[] WithTiffSize(byte[] tiff, uint width, uint height, uint? rowsPerStrip = null)
    {
        var patched = (byte[])tiff.Clone();
        if (patched[0] != (byte)'I')
        {
            throw new InvalidOperationException("only little-endian TIFF is patched here");
        }

        var ifd = (int)BinaryPrimitives.ReadUInt32LittleEndian(patched.AsSpan(4));
        var count = BinaryPrimitives.ReadUInt16LittleEndian(patched.AsSpan(ifd));
        var found = 0;
        for (var e = 0; e < count; e++)
        {
            var entry = patched.AsSpan(ifd + 2 + (e * 12), 12);
            var tag = BinaryPrimitives.ReadUInt16LittleEndian(entry);
            if (tag is 256 or 257 || (tag == 278 && rowsPerStrip is not null))
            {
                BinaryPrimitives.WriteUInt16LittleEndian(entry[2..], 4);
                BinaryPrimitives.WriteUInt32LittleEndian(entry[4..], 1);
                BinaryPrimitives.WriteUInt32LittleEndian(entry[8..], tag switch { 256 => width, 257 => height, _ => rowsPerStrip!.Value });
                found += tag == 278 ? 0 : 1;
            }
        }

        return found == 2 ? patched : throw new InvalidOperationException("the TIFF has no width or height tag");
    }
}
