namespace LaserEngrave.Core.Imaging;

/// <summary>Decodes Windows and OS/2 BMP files of every depth, compression and row order the BMP suite exercises.</summary>
/// <remarks>Our own decoder because SixLabors.ImageSharp is not on this machine's package source.</remarks>
internal static class BmpDecoder
{
    public static ImageInfo ReadInfo(ImageReader reader)
    {
        var header = BmpHeader.Read(reader);
        return Info(reader, header);
    }

    public static LoadedImage Decode(ImageReader reader)
    {
        var header = BmpHeader.Read(reader);
        var info = Info(reader, header);
        if (header.Compression == BmpCompression.Png)
        {
            return Rewrap(info, PngDecoder.Decode(reader, header.PixelOffset));
        }

        if (header.Compression == BmpCompression.Jpeg)
        {
            using var jpeg = EmbeddedJpeg(reader, header);
            return Rewrap(info, MagickDecoder.Decode(jpeg, ImageFormat.Jpeg));
        }

        if (header.IsRle)
        {
            return BmpRleDecoder.Decode(reader, header, info);
        }

        CheckPixelDataSize(reader, header);
        var width = header.Width;
        var height = header.Height;
        if (header.BitsPerPixel <= 8)
        {
            var palette = header.ReadPalette(reader);
            var bits = header.BitsPerPixel;
            ImageLimits.CheckIndexed(reader.Path, width, height, bits);
            var stride = (int)ImageLimits.IndexedStride(width, bits);
            var pixels = new byte[(long)stride * height];
            ReadRows(reader, header, (y, row) =>
            {
                var target = pixels.AsSpan((int)((long)y * stride), stride);
                row[..stride].CopyTo(target);
                IndexedPixels.ClearPadding(target, width, bits);
                CheckIndices(reader, target, y, width, bits, palette.Length);
            });
            return LoadedImage.Indexed(info, width, height, bits, palette, pixels);
        }

        ImageLimits.CheckFullColour(reader.Path, width, height);
        var rgba = new byte[(long)width * height * 4];
        var fields = new BmpBitFields(header);
        ReadRows(reader, header, (y, row) => fields.ConvertRow(row, rgba.AsSpan((int)((long)y * width * 4), width * 4), width));
        return LoadedImage.Rgba(info, width, height, rgba);
    }

    /// <summary>
    /// Builds the mask of an uncompressed palette BMP straight from the file, a row at a time, without holding the
    /// decoded image; null when the file or the options need the general path (compression, direct colour, dithering
    /// of a palette with greys).
    /// </summary>
    public static BitMask? TryBuildMask(ImageReader reader, MaskOptions options, out ImageInfo info)
    {
        var header = BmpHeader.Read(reader);
        info = Info(reader, header);
        if (header.Compression != BmpCompression.None || header.BitsPerPixel > 8)
        {
            return null;
        }

        CheckPixelDataSize(reader, header);
        var palette = header.ReadPalette(reader);
        var writer = PaletteMaskWriter.TryCreate(palette, header.BitsPerPixel, options);
        if (writer is null)
        {
            return null;
        }

        var mask = new BitMask(header.Width, header.Height);
        ReadRows(reader, header, (y, row) =>
        {
            CheckIndices(reader, row, y, header.Width, header.BitsPerPixel, palette.Length);
            writer.Write(row, mask.Row(y), header.Width);
        });
        return mask;
    }

    private static ImageInfo Info(ImageReader reader, BmpHeader header)
    {
        var info = header.ToInfo(reader.Path, reader.Length);
        ImageInfo embedded;
        switch (header.Compression)
        {
            case BmpCompression.Png:
                embedded = PngDecoder.ReadInfo(reader, header.PixelOffset);
                break;
            case BmpCompression.Jpeg:
                using (var jpeg = EmbeddedJpeg(reader, header))
                {
                    embedded = MagickDecoder.ReadInfo(jpeg, ImageFormat.Jpeg);
                }

                break;
            default:
                return info;
        }

        return info with
        {
            BitsPerPixel = embedded.BitsPerPixel,
            PaletteSize = embedded.PaletteSize,
            Width = embedded.Width,
            Height = embedded.Height,
            HasAlpha = embedded.HasAlpha,
            Interlaced = embedded.Interlaced,
            RowOrder = RowOrder.TopDown,
        };
    }

    /// <summary>A BMP's embedded PNG or JPEG decoded as a whole image, given the BMP's own metadata.</summary>
    private static LoadedImage Rewrap(ImageInfo info, LoadedImage inner) => inner.Layout == PixelLayout.Indexed
        ? LoadedImage.Indexed(info, inner.Width, inner.Height, inner.BitsPerIndex, inner.Palette.ToArray(), inner.PixelData)
        : LoadedImage.Rgba(info, inner.Width, inner.Height, inner.PixelData);

    /// <summary>The JPEG stream after the BMP headers, as its own source (ImageMagick reads a whole stream, not a part).</summary>
    private static ImageReader EmbeddedJpeg(ImageReader reader, BmpHeader header)
    {
        reader.Position = header.PixelOffset;
        var data = reader.ReadBlock(reader.Length - header.PixelOffset, "the embedded JPEG image");
        return new ImageReader(new MemoryStream(data, writable: false), reader.Path, ownsStream: true);
    }

    /// <summary>Refuses a file too short for its rows before anything is allocated for them.</summary>
    private static void CheckPixelDataSize(ImageReader reader, BmpHeader header)
    {
        // The last row's padding is sometimes left off by writers; its pixels are all that is needed.
        var needed = (header.FileStride * (header.Height - 1)) + header.RowBytes;
        var available = reader.Length - header.PixelOffset;
        if (needed > available)
        {
            throw reader.Fail(
                $"the file is truncated: {header.Height} rows of {header.Width} pixels at {header.BitsPerPixel} bits need {needed} bytes after offset {header.PixelOffset}, but only {available} remain");
        }
    }

    /// <summary>Reads the stored rows in file order and hands each over with its top-down row number.</summary>
    private static void ReadRows(ImageReader reader, BmpHeader header, RowHandler handler)
    {
        var stride = (int)header.FileStride;
        var rowBytes = header.RowBytes;
        var buffer = new byte[stride];
        reader.Position = header.PixelOffset;
        for (var i = 0; i < header.Height; i++)
        {
            var last = i == header.Height - 1;
            reader.ReadExactly(buffer.AsSpan(0, last ? rowBytes : stride), "a pixel row");
            handler(header.TopDown ? i : header.Height - 1 - i, buffer.AsSpan(0, rowBytes));
        }
    }

    private static void CheckIndices(ImageReader reader, ReadOnlySpan<byte> row, int y, int width, int bits, int paletteCount)
    {
        var bad = IndexedPixels.FindIndexOutside(row, width, bits, paletteCount);
        if (bad >= 0)
        {
            throw reader.Fail($"pixel ({bad}, {y}) uses colour index {IndexedPixels.Get(row, bad, bits)}, but the palette has only {paletteCount} colours");
        }
    }
}
