using System.Buffers.Binary;
using System.IO.Compression;

namespace LaserEngrave.Core.Imaging;

/// <summary>Decodes PNG: every colour type and bit depth, PLTE and tRNS, Adam7 interlacing.</summary>
/// <remarks>Our own decoder because SixLabors.ImageSharp is not on this machine's package source; zlib is the framework's ZLibStream.</remarks>
internal static class PngDecoder
{
    /// <summary>Deflate cannot expand data more than 1032-fold (a 258-byte match in two 1-bit codes), which bounds what a file can hold.</summary>
    private const long MaxDeflateRatio = 1032;

    private static readonly (int X, int Y, int DX, int DY)[] Adam7 =
    [
        (0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4), (1, 0, 2, 2), (0, 1, 1, 2),
    ];

    public static ImageInfo ReadInfo(ImageReader reader, long start = 0) =>
        PngHeader.Read(reader, start, wholeFile: false).ToInfo(reader.Path, reader.Length);

    public static LoadedImage Decode(ImageReader reader, long start = 0)
    {
        var png = PngHeader.Read(reader, start, wholeFile: true);
        var info = png.ToInfo(reader.Path, reader.Length);
        var width = png.Width;
        var height = png.Height;

        // Palette and grey images stay packed indices; grey becomes an index into a grey palette.
        var indexed = png.ColourType == 3 || (png.ColourType == 0 && (png.BitDepth <= 8 || png.Transparency is null));
        var outBits = png.ColourType == 0 && png.BitDepth == 16 ? 8 : png.BitDepth;
        if (indexed)
        {
            ImageLimits.CheckIndexed(reader.Path, width, height, outBits);
        }
        else
        {
            ImageLimits.CheckFullColour(reader.Path, width, height);
        }

        var rawBytes = RawSize(png);
        if (rawBytes > (png.IdatBytes * MaxDeflateRatio) + 1024)
        {
            throw reader.Fail($"the PNG's {png.IdatBytes} bytes of compressed data cannot hold a {width} x {height} image; the file is truncated or its header is wrong");
        }

        var palette = png.ColourType == 3 ? png.Palette : indexed ? GreyPalette(png, outBits) : [];
        var stride = indexed ? (int)ImageLimits.IndexedStride(width, outBits) : width * 4;
        var pixels = new byte[(long)stride * height];
        try
        {
            using var idat = new PngIdatStream(reader, png.FirstIdatOffset);
            using var zlib = new ZLibStream(idat, CompressionMode.Decompress);
            var passes = png.Interlaced ? Adam7 : [(0, 0, 1, 1)];
            foreach (var (x0, y0, dx, dy) in passes)
            {
                DecodePass(reader, png, zlib, pixels, stride, indexed, outBits, x0, y0, dx, dy);
            }

            idat.CheckRemainingChunks();
        }
        catch (InvalidDataException ex)
        {
            throw reader.Fail($"the PNG image data is corrupt ({ex.Message})");
        }

        if (png.ColourType == 3)
        {
            for (var y = 0; y < height; y++)
            {
                var row = pixels.AsSpan((int)((long)y * stride), stride);
                var bad = IndexedPixels.FindIndexOutside(row, width, outBits, palette.Length);
                if (bad >= 0)
                {
                    throw reader.Fail($"pixel ({bad}, {y}) uses colour index {IndexedPixels.Get(row, bad, outBits)}, but the palette has only {palette.Length} colours");
                }
            }
        }

        return indexed
            ? LoadedImage.Indexed(info, width, height, outBits, palette, pixels)
            : LoadedImage.Rgba(info, width, height, pixels);
    }

    private static long RawSize(PngHeader png)
    {
        var passes = png.Interlaced ? Adam7 : [(0, 0, 1, 1)];
        long total = 0;
        foreach (var (x0, y0, dx, dy) in passes)
        {
            var (w, h) = PassSize(png, x0, y0, dx, dy);
            if (w > 0 && h > 0)
            {
                total += h * (1 + ((((long)w * png.BitsPerPixel) + 7) / 8));
            }
        }

        return total;
    }

    private static (long W, long H) PassSize(PngHeader png, int x0, int y0, int dx, int dy) =>
        ((png.Width - x0 + dx - 1L) / dx, (png.Height - y0 + dy - 1L) / dy);

    private static Rgba32[] GreyPalette(PngHeader png, int bits)
    {
        var count = 1 << bits;
        var palette = new Rgba32[count];
        for (var i = 0; i < count; i++)
        {
            var v = (byte)(i * 255 / (count - 1));
            palette[i] = new Rgba32(v, v, v);
        }

        var transparent = png.TransparentGrey;
        if (transparent >= 0 && transparent < count)
        {
            palette[transparent] = palette[transparent] with { A = 0 };
        }

        return palette;
    }

    private static void DecodePass(
        ImageReader reader, PngHeader png, Stream zlib, byte[] pixels, int stride, bool indexed, int outBits, int x0, int y0, int dx, int dy)
    {
        var (passWidth, passHeight) = PassSize(png, x0, y0, dx, dy);
        if (passWidth <= 0 || passHeight <= 0)
        {
            return;
        }

        var width = (int)passWidth;
        var rowBytes = (int)((((long)width * png.BitsPerPixel) + 7) / 8);
        var filterStep = Math.Max(1, png.BitsPerPixel / 8);
        var current = new byte[rowBytes + 1];
        var previous = new byte[rowBytes + 1];
        for (var j = 0; j < passHeight; j++)
        {
            var read = zlib.ReadAtLeast(current, current.Length, throwOnEndOfStream: false);
            if (read < current.Length)
            {
                throw reader.Fail($"the PNG image data ends early (row {j} of {passHeight}{(png.Interlaced ? " in an interlace pass" : string.Empty)}); the file is truncated or corrupt");
            }

            Unfilter(reader, current[0], current.AsSpan(1), previous.AsSpan(1), filterStep);
            var y = y0 + (j * dy);
            var target = pixels.AsSpan((int)((long)y * stride), stride);
            var raw = current.AsSpan(1);
            if (indexed)
            {
                WriteIndexed(png, raw, target, width, outBits, x0, dx);
            }
            else
            {
                WriteRgba(png, raw, target, width, x0, dx);
            }

            (current, previous) = (previous, current);
        }
    }

    private static void Unfilter(ImageReader reader, byte filter, Span<byte> row, ReadOnlySpan<byte> previous, int step)
    {
        switch (filter)
        {
            case 0:
                break;
            case 1:
                for (var i = step; i < row.Length; i++)
                {
                    row[i] += row[i - step];
                }

                break;
            case 2:
                for (var i = 0; i < row.Length; i++)
                {
                    row[i] += previous[i];
                }

                break;
            case 3:
                for (var i = 0; i < row.Length; i++)
                {
                    var left = i >= step ? row[i - step] : 0;
                    row[i] += (byte)((left + previous[i]) >> 1);
                }

                break;
            case 4:
                for (var i = 0; i < row.Length; i++)
                {
                    int a = i >= step ? row[i - step] : 0, b = previous[i], c = i >= step ? previous[i - step] : 0;
                    int p = a + b - c, pa = Math.Abs(p - a), pb = Math.Abs(p - b), pc = Math.Abs(p - c);
                    row[i] += (byte)(pa <= pb && pa <= pc ? a : pb <= pc ? b : c);
                }

                break;
            default:
                throw reader.Fail($"the PNG image data is corrupt (unknown row filter {filter})");
        }
    }

    private static void WriteIndexed(PngHeader png, ReadOnlySpan<byte> raw, Span<byte> target, int width, int outBits, int x0, int dx)
    {
        if (png.BitDepth == 16)
        {
            for (var i = 0; i < width; i++)
            {
                IndexedPixels.Set(target, x0 + (i * dx), 8, Scale16(BinaryPrimitives.ReadUInt16BigEndian(raw[(2 * i)..])));
            }

            return;
        }

        if (dx == 1)
        {
            raw.CopyTo(target);
            IndexedPixels.ClearPadding(target, width, outBits);
            return;
        }

        for (var i = 0; i < width; i++)
        {
            IndexedPixels.Set(target, x0 + (i * dx), outBits, IndexedPixels.Get(raw, i, outBits));
        }
    }

    private static void WriteRgba(PngHeader png, ReadOnlySpan<byte> raw, Span<byte> target, int width, int x0, int dx)
    {
        var wide = png.BitDepth == 16;
        var trns = png.Transparency;
        for (var i = 0; i < width; i++)
        {
            var x = x0 + (i * dx);
            var o = target.Slice(x * 4, 4);
            switch (png.ColourType)
            {
                case 0:
                    var grey = Sample(raw, i, png.BitDepth);
                    o[0] = o[1] = o[2] = ScaleSample(grey, png.BitDepth);
                    o[3] = grey == png.TransparentGrey ? (byte)0 : (byte)255;
                    break;
                case 2:
                    int r = Sample(raw, 3 * i, png.BitDepth), g = Sample(raw, (3 * i) + 1, png.BitDepth), b = Sample(raw, (3 * i) + 2, png.BitDepth);
                    o[0] = ScaleSample(r, png.BitDepth);
                    o[1] = ScaleSample(g, png.BitDepth);
                    o[2] = ScaleSample(b, png.BitDepth);
                    o[3] = trns is not null
                        && r == BinaryPrimitives.ReadUInt16BigEndian(trns)
                        && g == BinaryPrimitives.ReadUInt16BigEndian(trns.AsSpan(2))
                        && b == BinaryPrimitives.ReadUInt16BigEndian(trns.AsSpan(4)) ? (byte)0 : (byte)255;
                    break;
                case 4:
                    o[0] = o[1] = o[2] = ScaleSample(Sample(raw, 2 * i, png.BitDepth), png.BitDepth);
                    o[3] = ScaleSample(Sample(raw, (2 * i) + 1, png.BitDepth), png.BitDepth);
                    break;
                default:
                    if (!wide)
                    {
                        raw.Slice(4 * i, 4).CopyTo(o);
                        break;
                    }

                    for (var c = 0; c < 4; c++)
                    {
                        o[c] = Scale16(BinaryPrimitives.ReadUInt16BigEndian(raw[((8 * i) + (2 * c))..]));
                    }

                    break;
            }
        }
    }

    /// <summary>Sample number <paramref name="n"/> of a row at 1 to 16 bits per sample.</summary>
    private static int Sample(ReadOnlySpan<byte> raw, int n, int bits) => bits switch
    {
        16 => BinaryPrimitives.ReadUInt16BigEndian(raw[(2 * n)..]),
        8 => raw[n],
        _ => IndexedPixels.Get(raw, n, bits),
    };

    private static byte ScaleSample(int value, int bits) => bits switch
    {
        8 => (byte)value,
        16 => Scale16(value),
        _ => (byte)(value * 255 / ((1 << bits) - 1)),
    };

    private static byte Scale16(int value) => (byte)(((value * 255) + 32767) / 65535);
}
