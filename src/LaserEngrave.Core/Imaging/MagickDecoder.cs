using System.Text.RegularExpressions;
using ImageMagick;

namespace LaserEngrave.Core.Imaging;

/// <summary>Decodes JPEG, TIFF and WebP through ImageMagick (Magick.NET) into a <see cref="LoadedImage"/>, within <see cref="ImageLimits"/>.</summary>
/// <remarks>
/// Every file is pinged (headers only) first and its size checked against <see cref="ImageLimits"/> before a pixel is
/// read, counting ImageMagick's pixel cache and, for TIFF, its strip buffer (<see cref="TiffDirectory"/>); a JPEG
/// must also be long enough for the picture it claims (<see cref="JpegFrame"/>).
/// ImageMagick's own resource limits are set from the same numbers, with no disk cache, so even a header that lies
/// cannot make it allocate more or spill to a temporary file. The coder is forced to the format the signature showed,
/// so no other ImageMagick coder or delegate program ever sees the file. A corrupt-image warning refuses the file:
/// ImageMagick would fill a truncated JPEG's missing rows with grey, and grey can burn.
/// </remarks>
internal static partial class MagickDecoder
{
    /// <summary>Palette colours an 8-bit index can reach; larger colour maps go through RGBA.</summary>
    private const int MaxPaletteColours = 256;

    private static readonly Lazy<bool> Limits = new(SetResourceLimits);

    public static ImageInfo ReadInfo(ImageReader reader, ImageFormat format) => Run(reader, format, () => Ping(reader, format).Info);

    public static LoadedImage Decode(ImageReader reader, ImageFormat format) => Run(reader, format, () =>
    {
        var pinged = Ping(reader, format);
        CheckCache(reader, format, pinged);
        if (format == ImageFormat.Jpeg && JpegFrame.Read(reader) is { IsHuffmanDct: true } frame && frame.MinimumScanBytes > reader.Length)
        {
            throw reader.Fail(
                $"the file is truncated: a {frame.Width} x {frame.Height} JPEG needs at least {frame.MinimumScanBytes} bytes of image data, but the file has {reader.Length}");
        }

        using var image = new MagickImage();
        string? corruption = null;
        image.Warning += (_, e) => corruption ??= e.Exception is MagickCorruptImageWarningException && !IsHarmless(e.Message) ? Describe(e.Message) : null;
        reader.Position = 0;
        image.Read(reader.BaseStream, Settings(format));
        if (corruption is not null)
        {
            throw reader.Fail($"the {Name(format)} data is corrupt or truncated ({corruption})");
        }

        // What a viewer shows: EXIF/TIFF orientation applied, colours in sRGB (CMYK JPEGs, YCbCr or Lab TIFFs).
        image.AutoOrient();
        if (image.ColorSpace is not (ColorSpace.sRGB or ColorSpace.Gray))
        {
            image.ColorSpace = ColorSpace.sRGB;
        }

        var info = pinged.Info with { Width = (int)image.Width, Height = (int)image.Height, HasAlpha = pinged.Info.HasAlpha || image.HasAlpha };
        using var pixels = image.GetPixelsUnsafe();
        if (!image.HasAlpha && image.ColorSpace == ColorSpace.Gray)
        {
            return image.Depth == 1 ? ToOneBit(reader, info, image, pixels) : ToGrey(reader, info, image, pixels);
        }

        if (!image.HasAlpha && image.ClassType == ClassType.Pseudo && image.ColormapSize is > 0 and <= MaxPaletteColours
            && pixels.GetChannelIndex(PixelChannel.Index) is { } indexChannel)
        {
            return ToPalette(reader, info, image, pixels, (int)indexChannel);
        }

        return ToRgba(reader, info, image, pixels);
    });

    /// <summary>Collapses an ImageMagick message to its reason: no file name, no source location, words split.</summary>
    internal static string Describe(string message)
    {
        var text = SourceLocation().Replace(FileName().Replace(message, string.Empty), string.Empty);
        text = string.Join(' ', text.Split((char[])['\r', '\n'], StringSplitOptions.RemoveEmptyEntries | StringSplitOptions.TrimEntries)).Trim(' ', ':', '.');
        if (text.Length == 0)
        {
            return "no reason given";
        }

        // Many reasons are bare tags such as "InsufficientImageDataInFile".
        return text.Contains(' ', StringComparison.Ordinal) ? text : CamelCaseBoundary().Replace(text, " $1").ToLowerInvariant();
    }

    /// <summary>
    /// Bytes between JPEG segments that libjpeg skips: common in camera files, and no pixel is lost, so every viewer shows
    /// them. Every other corrupt-data warning means rows were guessed.
    /// </summary>
    private static bool IsHarmless(string warning) => warning.Contains("extraneous bytes before marker", StringComparison.Ordinal);

    private static T Run<T>(ImageReader reader, ImageFormat format, Func<T> action)
    {
        try
        {
            _ = Limits.Value;
            return action();
        }
        catch (Exception ex) when (ex is MagickResourceLimitErrorException or MagickCacheErrorException)
        {
            throw new ImageLoadException(reader.Path, $"the {Name(format)} image needs more memory than the decoding limits allow ({Describe(ex.Message)})", ex);
        }
        catch (MagickCorruptImageErrorException ex)
        {
            throw new ImageLoadException(reader.Path, $"the {Name(format)} data is corrupt or truncated ({Describe(ex.Message)})", ex);
        }
        catch (MagickException ex)
        {
            throw new ImageLoadException(reader.Path, $"the {Name(format)} image cannot be decoded ({Describe(ex.Message)})", ex);
        }
        catch (Exception ex) when (ex is DllNotFoundException or TypeInitializationException or BadImageFormatException or EntryPointNotFoundException)
        {
            throw new ImageLoadException(
                reader.Path,
                $"{Name(format)} images need ImageMagick's native library, which cannot be loaded on this machine ({Describe(ex.Message)}); save the image as PNG or BMP and load that",
                ex);
        }
    }

    /// <summary>Sets ImageMagick's process-wide limits from <see cref="ImageLimits"/>; no other code in the process uses ImageMagick.</summary>
    private static bool SetResourceLimits()
    {
        ResourceLimits.Width = BitMask.MaxSide;
        ResourceLimits.Height = BitMask.MaxSide;
        ResourceLimits.Area = ImageLimits.MaxDecodedBytes;
        ResourceLimits.Memory = ImageLimits.MaxDecodedBytes;
        ResourceLimits.MaxMemoryRequest = ImageLimits.MaxDecodedBytes;

        // Without a disk cache, an image over the memory limit is refused instead of written to a temporary file.
        ResourceLimits.Disk = 0;
        ResourceLimits.ListLength = 2 * ImageInfo.MaxFramesCounted;
        return true;
    }

    private static MagickReadSettings Settings(ImageFormat format, uint frameCount = 1) => new()
    {
        Format = format switch
        {
            ImageFormat.Jpeg => MagickFormat.Jpeg,
            ImageFormat.Tiff => MagickFormat.Tiff,
            ImageFormat.WebP => MagickFormat.WebP,
            _ => throw new ArgumentOutOfRangeException(nameof(format), format, "not an ImageMagick format here"),
        },
        FrameIndex = 0,
        FrameCount = frameCount,
    };

    private static string Name(ImageFormat format) => format switch
    {
        ImageFormat.Jpeg => "JPEG",
        ImageFormat.Tiff => "TIFF",
        ImageFormat.WebP => "WebP",
        _ => format.ToString(),
    };

    private static Pinged Ping(ImageReader reader, ImageFormat format)
    {
        var tiff = format == ImageFormat.Tiff ? TiffDirectory.Read(reader) : null;
        using var image = new MagickImage();
        reader.Position = 0;
        image.Ping(reader.BaseStream, Settings(format));
        long width = image.Width, height = image.Height;
        ImageLimits.CheckDimensions(reader.Path, width, height);

        var samples = image.ColorType switch
        {
            ColorType.Bilevel or ColorType.Grayscale or ColorType.Palette => 1,
            ColorType.GrayscaleAlpha or ColorType.PaletteAlpha or ColorType.PaletteBilevelAlpha => 2,
            ColorType.TrueColorAlpha or ColorType.ColorSeparation => 4,
            ColorType.ColorSeparationAlpha => 5,
            _ => 3,
        };
        var palette = image.ColorType is ColorType.Palette or ColorType.PaletteAlpha or ColorType.PaletteBilevelAlpha ? Math.Max(0, image.ColormapSize) : 0;

        // The pixel cache holds one byte per channel (Q8), plus an index channel for palette and grey images; alpha may
        // show up only when the pixels are read (TIFF extra samples), so colour counts it anyway.
        var cacheChannels = image.ColorType switch
        {
            ColorType.Bilevel or ColorType.Grayscale => 2,
            ColorType.GrayscaleAlpha => 3,
            ColorType.ColorSeparationAlpha or ColorType.PaletteAlpha => 5,
            _ => 4,
        };

        double? dpiX = null, dpiY = null;
        var perInch = image.Density.Units switch
        {
            DensityUnit.PixelsPerInch => 1.0,
            DensityUnit.PixelsPerCentimeter => 2.54,
            _ => 0.0,
        };
        if (perInch > 0 && image.Density.X > 0 && image.Density.Y > 0)
        {
            (dpiX, dpiY) = (image.Density.X * perInch, image.Density.Y * perInch);
        }

        // Orientations 5 to 8 turn the picture a quarter, so the shown width is the stored height.
        if (image.Orientation is Orientation.LeftTop or Orientation.RightTop or Orientation.RightBottom or Orientation.LeftBottom)
        {
            (width, height) = (height, width);
            (dpiX, dpiY) = (dpiY, dpiX);
        }

        var info = new ImageInfo(
            reader.Path,
            format,
            BitsPerPixel: (int)Math.Min(int.MaxValue, image.Depth * (long)samples),
            PaletteSize: palette,
            Width: (int)width,
            Height: (int)height,
            FileSizeBytes: reader.Length,
            DpiX: dpiX,
            DpiY: dpiY,
            RowOrder: RowOrder.TopDown,
            Compression: Compression(reader, format, image.Compression),
            HasAlpha: image.HasAlpha,
            Interlaced: image.Interlace is not (Interlace.NoInterlace or Interlace.Undefined),
            FrameCount: format == ImageFormat.Jpeg ? 1 : CountFrames(reader, format));
        return new Pinged(info, cacheChannels, tiff?.BufferBytes(image.Width, image.Height) ?? 0);
    }

    /// <summary>Pages (TIFF) or frames (WebP) up to <see cref="ImageInfo.MaxFramesCounted"/>; null when a later one cannot be read.</summary>
    private static int? CountFrames(ImageReader reader, ImageFormat format)
    {
        try
        {
            reader.Position = 0;
            return MagickImageInfo.ReadCollection(reader.BaseStream, Settings(format, ImageInfo.MaxFramesCounted)).Count();
        }
        catch (MagickException)
        {
            // The first page decides whether the file loads; a broken later page only leaves the count unknown.
            return null;
        }
    }

    private static string Compression(ImageReader reader, ImageFormat format, CompressionMethod method) => method switch
    {
        CompressionMethod.NoCompression => "none",
        CompressionMethod.JPEG => "JPEG",
        CompressionMethod.LosslessJPEG => "lossless JPEG",
        CompressionMethod.LZW => "LZW",
        CompressionMethod.Zip or CompressionMethod.ZipS => "deflate",
        CompressionMethod.RLE => "PackBits",
        CompressionMethod.Fax => "CCITT G3",
        CompressionMethod.Group4 => "CCITT G4",
        CompressionMethod.Undefined when format == ImageFormat.WebP => WebPCodec(reader),
        _ => method.ToString(),
    };

    /// <summary>The first chunk of a WebP names its coding: VP8 lossy, VP8L lossless, VP8X extended (alpha, animation, metadata).</summary>
    private static string WebPCodec(ImageReader reader)
    {
        Span<byte> chunk = stackalloc byte[4];
        reader.Position = 12;
        var n = reader.ReadAtMost(chunk);
        return n < 4 ? "unknown" : chunk switch
        {
            [(byte)'V', (byte)'P', (byte)'8', (byte)' '] => "VP8 (lossy)",
            [(byte)'V', (byte)'P', (byte)'8', (byte)'L'] => "VP8L (lossless)",
            [(byte)'V', (byte)'P', (byte)'8', (byte)'X'] => "VP8X (extended)",
            _ => "unknown",
        };
    }

    private static void CheckCache(ImageReader reader, ImageFormat format, Pinged pinged)
    {
        var bytes = ((long)pinged.Info.Width * pinged.Info.Height * pinged.CacheChannels) + pinged.ReadBufferBytes;
        if (bytes <= ImageLimits.MaxDecodedBytes)
        {
            return;
        }

        var advice = pinged.ReadBufferBytes > ImageLimits.MaxDecodedBytes / 4
            ? $" (its strips are read {pinged.ReadBufferBytes >> 20} MB at a time); save it with smaller strips, or as a 1-bit BMP"
            : string.Empty;
        throw reader.Fail(
            $"a {pinged.Info.Width} x {pinged.Info.Height} {Name(format)} image needs {bytes >> 20} MB to decode, more than the {ImageLimits.MaxDecodedBytes >> 20} MB limit{advice}");
    }

    /// <summary>1-bit grey (bilevel TIFF) stays 1 bit per pixel, so a 20000 x 20000 page takes 50 MB.</summary>
    private static LoadedImage ToOneBit(ImageReader reader, ImageInfo info, MagickImage image, IUnsafePixelCollection<byte> pixels)
    {
        int width = (int)image.Width, height = (int)image.Height, channels = (int)image.ChannelCount;
        var grey = GreyChannel(pixels);
        ImageLimits.CheckIndexed(reader.Path, width, height, 1);
        var stride = (int)ImageLimits.IndexedStride(width, 1);
        var packed = new byte[(long)stride * height];
        for (var y = 0; y < height; y++)
        {
            var source = pixels.GetReadOnlyArea(0, y, (uint)width, 1);
            var target = packed.AsSpan((int)((long)y * stride), stride);
            for (var x = 0; x < width; x++)
            {
                if (source[(x * channels) + grey] >= 128)
                {
                    target[x >> 3] |= (byte)(0x80 >> (x & 7));
                }
            }
        }

        return LoadedImage.Indexed(info, width, height, 1, [Rgba32.Black, Rgba32.White], packed);
    }

    private static LoadedImage ToGrey(ImageReader reader, ImageInfo info, MagickImage image, IUnsafePixelCollection<byte> pixels)
    {
        int width = (int)image.Width, height = (int)image.Height, channels = (int)image.ChannelCount;
        var indices = OneChannel(reader, pixels, width, height, channels, GreyChannel(pixels));

        var ramp = new Rgba32[256];
        for (var i = 0; i < ramp.Length; i++)
        {
            ramp[i] = new Rgba32((byte)i, (byte)i, (byte)i);
        }

        return LoadedImage.Indexed(info, width, height, 8, ramp, indices);
    }

    /// <summary>Palette images keep their indices, so the palette decides what burns, as for BMP, PNG and GIF.</summary>
    private static LoadedImage ToPalette(ImageReader reader, ImageInfo info, MagickImage image, IUnsafePixelCollection<byte> pixels, int indexChannel)
    {
        int width = (int)image.Width, height = (int)image.Height, channels = (int)image.ChannelCount;
        var palette = new Rgba32[image.ColormapSize];
        for (var i = 0; i < palette.Length; i++)
        {
            var colour = image.GetColormapColor(i) ?? throw reader.Fail($"palette entry {i} of {palette.Length} is missing");
            palette[i] = new Rgba32(colour.R, colour.G, colour.B);
        }

        var indices = OneChannel(reader, pixels, width, height, channels, indexChannel);
        for (var y = 0; y < height; y++)
        {
            var target = indices.AsSpan((int)((long)y * width), width);
            var bad = IndexedPixels.FindIndexOutside(target, width, 8, palette.Length);
            if (bad >= 0)
            {
                throw reader.Fail($"pixel ({bad}, {y}) uses colour index {target[bad]}, but the palette has only {palette.Length} colours");
            }
        }

        return LoadedImage.Indexed(info, width, height, 8, palette, indices);
    }

    /// <summary>One 8-bit channel of every pixel (grey level or palette index), row after row.</summary>
    private static byte[] OneChannel(ImageReader reader, IUnsafePixelCollection<byte> pixels, int width, int height, int channels, int channel)
    {
        ImageLimits.CheckIndexed(reader.Path, width, height, 8);
        var values = new byte[(long)width * height];
        for (var y = 0; y < height; y++)
        {
            var source = pixels.GetReadOnlyArea(0, y, (uint)width, 1);
            var target = values.AsSpan((int)((long)y * width), width);
            for (var x = 0; x < width; x++)
            {
                target[x] = source[(x * channels) + channel];
            }
        }

        return values;
    }

    private static LoadedImage ToRgba(ImageReader reader, ImageInfo info, MagickImage image, IUnsafePixelCollection<byte> pixels)
    {
        int width = (int)image.Width, height = (int)image.Height, channels = (int)image.ChannelCount;
        var red = Channel(pixels, PixelChannel.Red);
        var isGrey = image.ColorSpace == ColorSpace.Gray;
        var green = isGrey ? red : Channel(pixels, PixelChannel.Green);
        var blue = isGrey ? red : Channel(pixels, PixelChannel.Blue);
        var alpha = image.HasAlpha ? Channel(pixels, PixelChannel.Alpha) : -1;
        ImageLimits.CheckFullColour(reader.Path, width, height);
        var rgba = new byte[(long)width * height * 4];
        for (var y = 0; y < height; y++)
        {
            var source = pixels.GetReadOnlyArea(0, y, (uint)width, 1);
            var target = rgba.AsSpan((int)((long)y * width * 4), width * 4);
            for (var x = 0; x < width; x++)
            {
                var s = x * channels;
                var t = x * 4;
                target[t] = source[s + red];
                target[t + 1] = source[s + green];
                target[t + 2] = source[s + blue];
                target[t + 3] = alpha < 0 ? byte.MaxValue : source[s + alpha];
            }
        }

        return LoadedImage.Rgba(info, width, height, rgba);
    }

    private static int GreyChannel(IUnsafePixelCollection<byte> pixels) => Channel(pixels, PixelChannel.Gray);

    private static int Channel(IUnsafePixelCollection<byte> pixels, PixelChannel channel) =>
        pixels.GetChannelIndex(channel) is { } index ? (int)index : throw new MagickCorruptImageErrorException($"the decoded pixels have no {channel} channel");

    [GeneratedRegex(@"\s*`[^`']*'")]
    private static partial Regex FileName();

    [GeneratedRegex(@"\s*@\s*(error|warning|fatal)/\S*\s*$")]
    private static partial Regex SourceLocation();

    [GeneratedRegex(@"(?<=[a-z])([A-Z])")]
    private static partial Regex CamelCaseBoundary();

    /// <summary>What a ping found, the bytes per pixel of ImageMagick's pixel cache, and the bytes of its TIFF read buffer.</summary>
    private sealed record Pinged(ImageInfo Info, int CacheChannels, long ReadBufferBytes);
}
