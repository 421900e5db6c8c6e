namespace LaserEngrave.Core.Imaging;

/// <summary>Decodes Netpbm images: PBM (P1, P4), PGM (P2, P5) and PPM (P3, P6), maxval up to 65535.</summary>
/// <remarks>
/// Our own decoder because SixLabors.ImageSharp is not on this machine's package source. PBM's 1 is black, so a PBM
/// becomes a 1-bit image with the palette white, black; PGM becomes 8-bit indices into a grey palette.
/// </remarks>
internal static class NetpbmDecoder
{
    public static ImageInfo ReadInfo(ImageReader reader) => ReadHeader(reader, out _).Info;

    public static LoadedImage Decode(ImageReader reader)
    {
        var (info, magic, maxValue) = ReadHeader(reader, out var tokens);
        int width = info.Width, height = info.Height;
        var plain = magic <= 3;
        var samplesPerPixel = info.Format == ImageFormat.Ppm ? 3 : 1;
        var samples = (long)width * height * samplesPerPixel;
        var bytesPerSample = maxValue > 255 ? 2 : 1;

        // Check the file can hold the pixels before allocating them: raw samples have a fixed size, plain ones take
        // at least one character each (PBM) or a digit and a separator (PGM, PPM).
        var needed = magic switch
        {
            1 => samples,
            2 or 3 => (2 * samples) - 1,
            4 => ImageLimits.IndexedStride(width, 1) * height,
            _ => samples * bytesPerSample,
        };
        var available = plain ? tokens.Remaining : reader.Remaining;
        if (needed > available)
        {
            throw reader.Fail($"the file is truncated: a {width} x {height} {info.Format.ToString().ToUpperInvariant()} needs at least {needed} bytes of pixels, but only {available} remain");
        }

        return info.Format switch
        {
            ImageFormat.Pbm => DecodeBitmap(reader, tokens, info, plain),
            ImageFormat.Pgm => DecodeGreymap(reader, tokens, info, plain, maxValue),
            _ => DecodePixmap(reader, tokens, info, plain, maxValue),
        };
    }

    private static (ImageInfo Info, int Magic, int MaxValue) ReadHeader(ImageReader reader, out NetpbmTokenizer tokens)
    {
        reader.Position = 0;
        tokens = new NetpbmTokenizer(reader);
        if (tokens.ReadByte() != 'P')
        {
            throw reader.Fail("not a Netpbm file (no \"P\" magic)");
        }

        var magic = tokens.ReadByte() - '0';
        if (magic is < 1 or > 6)
        {
            throw reader.Fail($"P{(char)(magic + '0')} is not a Netpbm format this decoder reads (P1 to P6)");
        }

        var format = magic switch
        {
            1 or 4 => ImageFormat.Pbm,
            2 or 5 => ImageFormat.Pgm,
            _ => ImageFormat.Ppm,
        };
        var width = tokens.ReadNumber("width");
        var height = tokens.ReadNumber("height");
        ImageLimits.CheckDimensions(reader.Path, width, height);
        var maxValue = 1;
        if (format != ImageFormat.Pbm)
        {
            maxValue = tokens.ReadNumber("maxval");
            if (maxValue is < 1 or > 65535)
            {
                throw reader.Fail($"the Netpbm maxval {maxValue} is not 1 to 65535");
            }
        }

        if (magic >= 4)
        {
            // Exactly one whitespace byte separates a raw header from the pixels.
            if (!NetpbmTokenizer.IsSpace(tokens.ReadByte()))
            {
                throw reader.Fail("the Netpbm header does not end in whitespace");
            }

            reader.Position = tokens.Position;
        }

        var depth = maxValue > 255 ? 16 : 8;
        var info = new ImageInfo(
            reader.Path,
            format,
            format switch
            {
                ImageFormat.Pbm => 1,
                ImageFormat.Pgm => depth,
                _ => 3 * depth,
            },
            0,
            width,
            height,
            reader.Length,
            null,
            null,
            RowOrder.TopDown,
            magic <= 3 ? "ASCII" : "none",
            false);
        return (info, magic, maxValue);
    }

    private static LoadedImage DecodeBitmap(ImageReader reader, NetpbmTokenizer tokens, ImageInfo info, bool plain)
    {
        int width = info.Width, height = info.Height;
        ImageLimits.CheckIndexed(reader.Path, width, height, 1);
        var stride = (int)ImageLimits.IndexedStride(width, 1);
        var pixels = new byte[(long)stride * height];
        for (var y = 0; y < height; y++)
        {
            var row = pixels.AsSpan((int)((long)y * stride), stride);
            if (plain)
            {
                for (var x = 0; x < width; x++)
                {
                    var bit = tokens.ReadBit();
                    row[x >> 3] |= (byte)(bit << (7 - (x & 7)));
                }
            }
            else
            {
                reader.ReadExactly(row, "a PBM row");
                IndexedPixels.ClearPadding(row, width, 1);
            }
        }

        return LoadedImage.Indexed(info, width, height, 1, [Rgba32.White, Rgba32.Black], pixels);
    }

    private static LoadedImage DecodeGreymap(ImageReader reader, NetpbmTokenizer tokens, ImageInfo info, bool plain, int maxValue)
    {
        int width = info.Width, height = info.Height;
        ImageLimits.CheckIndexed(reader.Path, width, height, 8);

        // Up to 255 levels index the grey palette directly; deeper files are scaled to 256 levels.
        var levels = Math.Min(maxValue, 255) + 1;
        var palette = new Rgba32[levels];
        for (var i = 0; i < levels; i++)
        {
            var v = (byte)(((i * 255) + ((levels - 1) / 2)) / (levels - 1));
            palette[i] = new Rgba32(v, v, v);
        }

        var pixels = new byte[(long)width * height];
        var sampleRow = new byte[width * (maxValue > 255 ? 2 : 1)];
        for (var y = 0; y < height; y++)
        {
            var row = pixels.AsSpan((int)((long)y * width), width);
            if (!plain)
            {
                reader.ReadExactly(sampleRow, "a PGM row");
            }

            for (var x = 0; x < width; x++)
            {
                var v = plain ? tokens.ReadNumber("grey sample") : RawSample(sampleRow, x, maxValue);
                row[x] = maxValue > 255 ? Scale(reader, v, maxValue) : CheckSample(reader, v, maxValue);
            }
        }

        return LoadedImage.Indexed(info, width, height, 8, palette, pixels);
    }

    private static LoadedImage DecodePixmap(ImageReader reader, NetpbmTokenizer tokens, ImageInfo info, bool plain, int maxValue)
    {
        int width = info.Width, height = info.Height;
        ImageLimits.CheckFullColour(reader.Path, width, height);
        var rgba = new byte[(long)width * height * 4];
        var sampleRow = new byte[width * 3 * (maxValue > 255 ? 2 : 1)];
        for (var y = 0; y < height; y++)
        {
            if (!plain)
            {
                reader.ReadExactly(sampleRow, "a PPM row");
            }

            var row = rgba.AsSpan((int)((long)y * width * 4), width * 4);
            for (var x = 0; x < width; x++)
            {
                for (var c = 0; c < 3; c++)
                {
                    var v = plain ? tokens.ReadNumber("colour sample") : RawSample(sampleRow, (3 * x) + c, maxValue);
                    row[(4 * x) + c] = Scale(reader, v, maxValue);
                }

                row[(4 * x) + 3] = 255;
            }
        }

        return LoadedImage.Rgba(info, width, height, rgba);
    }

    private static int RawSample(byte[] row, int n, int maxValue) =>
        maxValue > 255 ? (row[2 * n] << 8) | row[(2 * n) + 1] : row[n];

    private static byte CheckSample(ImageReader reader, int value, int maxValue) =>
        value <= maxValue ? (byte)value : throw reader.Fail($"a Netpbm sample {value} exceeds the maxval {maxValue}");

    private static byte Scale(ImageReader reader, int value, int maxValue) =>
        (byte)(((CheckSampleWide(reader, value, maxValue) * 255L) + (maxValue / 2)) / maxValue);

    private static int CheckSampleWide(ImageReader reader, int value, int maxValue) =>
        value <= maxValue ? value : throw reader.Fail($"a Netpbm sample {value} exceeds the maxval {maxValue}");
}
