using System.Buffers.Binary;

namespace LaserEngrave.Core.Imaging;

/// <summary>The parsed and checked headers of a BMP file: file header, info header of any version, bit masks and palette place.</summary>
internal sealed record BmpHeader
{
    private const int FileHeaderSize = 14;

    public required int HeaderSize { get; init; }

    public required string Version { get; init; }

    public required int Width { get; init; }

    public required int Height { get; init; }

    public required bool TopDown { get; init; }

    public required int BitsPerPixel { get; init; }

    public required BmpCompression Compression { get; init; }

    public required long PixelOffset { get; init; }

    public required long PaletteOffset { get; init; }

    public required int PaletteEntrySize { get; init; }

    /// <summary>Palette entries the pixels may index (at most 2^bits); 0 for direct colour.</summary>
    public required int PaletteCount { get; init; }

    public required uint RedMask { get; init; }

    public required uint GreenMask { get; init; }

    public required uint BlueMask { get; init; }

    public required uint AlphaMask { get; init; }

    public required int XPelsPerMetre { get; init; }

    public required int YPelsPerMetre { get; init; }

    /// <summary>Bytes of pixel data the header declares (biSizeImage); only trusted for compressed data, and only when the file holds them.</summary>
    public required long ImageSize { get; init; }

    public bool IsIndexed => BitsPerPixel <= 8 && Compression is BmpCompression.None or BmpCompression.Rle4 or BmpCompression.Rle8;

    public bool IsRle => Compression is BmpCompression.Rle4 or BmpCompression.Rle8 or BmpCompression.Rle24;

    public string CompressionName => Compression switch
    {
        BmpCompression.None => "none",
        BmpCompression.Rle8 => "RLE8",
        BmpCompression.Rle4 => "RLE4",
        BmpCompression.Rle24 => "RLE24",
        BmpCompression.BitFields => "BITFIELDS",
        BmpCompression.AlphaBitFields => "ALPHABITFIELDS",
        BmpCompression.Jpeg => "JPEG",
        BmpCompression.Png => "PNG",
        BmpCompression.Huffman1D => "Huffman 1D",
        _ => "CMYK",
    };

    /// <summary>Bytes per stored row: the pixels rounded up to a multiple of 4 bytes.</summary>
    public long FileStride => (((long)Width * BitsPerPixel) + 31) / 32 * 4;

    /// <summary>Bytes of pixels in a row, without the padding.</summary>
    public int RowBytes => (int)((((long)Width * BitsPerPixel) + 7) / 8);

    public ImageInfo ToInfo(string path, long fileSize) => new(
        path,
        ImageFormat.Bmp,
        BitsPerPixel,
        PaletteCount,
        Width,
        Height,
        fileSize,
        ImageInfo.DpiFromPixelsPerMetre(XPelsPerMetre),
        ImageInfo.DpiFromPixelsPerMetre(YPelsPerMetre),
        TopDown ? RowOrder.TopDown : RowOrder.BottomUp,
        CompressionName,
        HasAlpha: AlphaMask != 0);

    /// <summary>Reads and checks every header field before anything is sized from them.</summary>
    public static BmpHeader Read(ImageReader reader)
    {
        reader.Position = 0;
        Span<byte> fileHeader = stackalloc byte[FileHeaderSize + 4];
        reader.ReadExactly(fileHeader, "the BMP file header");
        if (fileHeader[0] != (byte)'B' || fileHeader[1] != (byte)'M')
        {
            throw reader.Fail("not a BMP file (no \"BM\" signature)");
        }

        var pixelOffset = (long)BinaryPrimitives.ReadUInt32LittleEndian(fileHeader[10..]);
        var headerSize = BinaryPrimitives.ReadUInt32LittleEndian(fileHeader[14..]);
        var version = headerSize switch
        {
            12 => "OS/2 v1",
            40 => "Windows v3",
            52 => "Windows v3 with RGB masks (52-byte header)",
            56 => "Windows v3 with RGBA masks (56-byte header)",
            108 => "Windows v4",
            124 => "Windows v5",
            >= 16 and <= 64 => "OS/2 v2",
            _ => throw reader.Fail($"BMP info header size {headerSize} is not a known BMP version (12, 16-64, 108 or 124 bytes)"),
        };
        var os2v2 = version == "OS/2 v2";

        var header = new byte[headerSize];
        BinaryPrimitives.WriteUInt32LittleEndian(header, headerSize);
        reader.ReadExactly(header.AsSpan(4), "the BMP info header");

        int width, height, planes, bits;
        var compressionCode = 0u;
        long imageSize = 0;
        int xPels = 0, yPels = 0;
        var colorsUsed = 0u;
        if (headerSize == 12)
        {
            width = BinaryPrimitives.ReadUInt16LittleEndian(header.AsSpan(4));
            height = BinaryPrimitives.ReadUInt16LittleEndian(header.AsSpan(6));
            planes = BinaryPrimitives.ReadUInt16LittleEndian(header.AsSpan(8));
            bits = BinaryPrimitives.ReadUInt16LittleEndian(header.AsSpan(10));
        }
        else
        {
            width = BinaryPrimitives.ReadInt32LittleEndian(header.AsSpan(4));
            height = BinaryPrimitives.ReadInt32LittleEndian(header.AsSpan(8));
            planes = BinaryPrimitives.ReadUInt16LittleEndian(header.AsSpan(12));
            bits = BinaryPrimitives.ReadUInt16LittleEndian(header.AsSpan(14));
            compressionCode = Field(header, 16);
            imageSize = Field(header, 20);
            xPels = (int)Field(header, 24);
            yPels = (int)Field(header, 28);
            colorsUsed = Field(header, 32);
        }

        if (planes != 1)
        {
            throw reader.Fail($"the BMP header says {planes} colour planes; it must be 1");
        }

        if (width <= 0)
        {
            throw reader.Fail($"the BMP width {width} is not positive");
        }

        if (height == 0 || height == int.MinValue)
        {
            throw reader.Fail($"the BMP height {height} is not valid");
        }

        var topDown = height < 0;
        height = Math.Abs(height);

        var compression = (compressionCode, os2v2) switch
        {
            (0, _) => BmpCompression.None,
            (1, _) => BmpCompression.Rle8,
            (2, _) => BmpCompression.Rle4,
            (3, false) => BmpCompression.BitFields,
            (3, true) => BmpCompression.Huffman1D,
            (4, false) => BmpCompression.Jpeg,
            (4, true) => BmpCompression.Rle24,
            (5, false) => BmpCompression.Png,
            (6, false) => BmpCompression.AlphaBitFields,
            (11 or 12 or 13, false) => BmpCompression.Cmyk,
            _ => throw reader.Fail($"BMP compression {compressionCode} is not a known encoding"),
        };

        CheckBitsAndCompression(reader, bits, compression, topDown);
        ImageLimits.CheckDimensions(reader.Path, width, height);

        // Bit masks live in the header from 52 bytes on; a 40-byte header with BITFIELDS has them right after it.
        var masksAfterHeader = 0;
        uint red, green, blue, alpha = 0;
        if (compression is BmpCompression.BitFields or BmpCompression.AlphaBitFields)
        {
            Span<byte> masks = stackalloc byte[16];
            if (headerSize >= 52)
            {
                header.AsSpan(40, headerSize >= 56 ? 16 : 12).CopyTo(masks);
            }
            else
            {
                masksAfterHeader = compression == BmpCompression.AlphaBitFields ? 16 : 12;
                reader.ReadExactly(masks[..masksAfterHeader], "the BMP bit masks");
            }

            red = BinaryPrimitives.ReadUInt32LittleEndian(masks);
            green = BinaryPrimitives.ReadUInt32LittleEndian(masks[4..]);
            blue = BinaryPrimitives.ReadUInt32LittleEndian(masks[8..]);
            alpha = BinaryPrimitives.ReadUInt32LittleEndian(masks[12..]);
        }
        else if (bits == 16)
        {
            (red, green, blue) = (0x7C00u, 0x03E0u, 0x001Fu);
        }
        else
        {
            (red, green, blue) = (0x00FF0000u, 0x0000FF00u, 0x000000FFu);
        }

        if (compression is BmpCompression.BitFields or BmpCompression.AlphaBitFields)
        {
            CheckMasks(reader, bits, red, green, blue, alpha);
        }

        var paletteOffset = FileHeaderSize + headerSize + masksAfterHeader;
        var entrySize = headerSize == 12 ? 3 : 4;
        if (pixelOffset < paletteOffset || pixelOffset > reader.Length)
        {
            throw reader.Fail($"the BMP pixel data offset {pixelOffset} is outside the file (headers end at {paletteOffset}, file has {reader.Length} bytes)");
        }

        var paletteCount = 0;
        var declared = (long)colorsUsed;
        if (bits <= 8 && compression is not (BmpCompression.Png or BmpCompression.Jpeg))
        {
            var maxColours = 1 << bits;
            if (declared == 0 || headerSize == 12)
            {
                declared = maxColours;
            }

            if (paletteOffset + (declared * entrySize) > reader.Length)
            {
                throw reader.Fail($"the BMP palette claims {declared} colours, more than the file holds");
            }

            // OS/2 files and some writers leave the palette shorter than declared; the pixel offset says where it really ends.
            var room = (pixelOffset - paletteOffset) / entrySize;
            paletteCount = (int)Math.Min(Math.Min(declared, maxColours), room);
            if (paletteCount < 1)
            {
                throw reader.Fail($"the BMP has {bits} bits per pixel but no palette");
            }
        }

        return new BmpHeader
        {
            HeaderSize = (int)headerSize,
            Version = version,
            Width = width,
            Height = height,
            TopDown = topDown,
            BitsPerPixel = bits,
            Compression = compression,
            PixelOffset = pixelOffset,
            PaletteOffset = paletteOffset,
            PaletteEntrySize = entrySize,
            PaletteCount = paletteCount,
            RedMask = red,
            GreenMask = green,
            BlueMask = blue,
            AlphaMask = alpha,
            XPelsPerMetre = xPels,
            YPelsPerMetre = yPels,
            ImageSize = imageSize,
        };
    }

    /// <summary>The palette, opaque (BMP's fourth palette byte is reserved, not alpha).</summary>
    public Rgba32[] ReadPalette(ImageReader reader)
    {
        reader.Position = PaletteOffset;
        var raw = reader.ReadBlock((long)PaletteCount * PaletteEntrySize, "the BMP palette");
        var palette = new Rgba32[PaletteCount];
        for (var i = 0; i < PaletteCount; i++)
        {
            var e = raw.AsSpan(i * PaletteEntrySize);
            palette[i] = new Rgba32(e[2], e[1], e[0]);
        }

        return palette;
    }

    // An OS/2 v2 header may stop after any field; fields it leaves out read as zero.
    private static uint Field(byte[] header, int offset) =>
        offset + 4 <= header.Length ? BinaryPrimitives.ReadUInt32LittleEndian(header.AsSpan(offset)) : 0;

    private static void CheckBitsAndCompression(ImageReader reader, int bits, BmpCompression compression, bool topDown)
    {
        switch (compression)
        {
            case BmpCompression.Huffman1D:
                throw reader.Fail("OS/2 BMP with Huffman 1D compression is not supported; save it as an uncompressed BMP or PNG");
            case BmpCompression.Cmyk:
                throw reader.Fail("CMYK BMP is not supported; save it as an RGB BMP or PNG");
            case BmpCompression.Png or BmpCompression.Jpeg:
                return;
        }

        if (bits == 64)
        {
            throw reader.Fail("64-bit (high dynamic range) BMP is not supported; save it as a 24- or 32-bit BMP or PNG");
        }

        if (bits is not (1 or 2 or 4 or 8 or 16 or 24 or 32))
        {
            throw reader.Fail($"{bits} bits per pixel is not a valid BMP depth (1, 2, 4, 8, 16, 24 or 32)");
        }

        var expected = compression switch
        {
            BmpCompression.Rle8 => 8,
            BmpCompression.Rle4 => 4,
            BmpCompression.Rle24 => 24,
            _ => 0,
        };
        if (expected != 0 && bits != expected)
        {
            throw reader.Fail($"{compression.ToString().ToUpperInvariant()} compression needs {expected} bits per pixel, but the header says {bits}");
        }

        if (compression is BmpCompression.BitFields or BmpCompression.AlphaBitFields && bits is not (16 or 32))
        {
            throw reader.Fail($"BITFIELDS needs 16 or 32 bits per pixel, but the header says {bits}");
        }

        if (expected != 0 && topDown)
        {
            throw reader.Fail("an RLE-compressed BMP cannot be stored top-down (negative height)");
        }
    }

    private static void CheckMasks(ImageReader reader, int bits, uint red, uint green, uint blue, uint alpha)
    {
        if ((red | green | blue) == 0)
        {
            throw reader.Fail("the BMP bit masks are all zero");
        }

        var usable = bits == 32 ? uint.MaxValue : (1u << bits) - 1;
        foreach (var (name, mask) in new[] { ("red", red), ("green", green), ("blue", blue), ("alpha", alpha) })
        {
            if ((mask & ~usable) != 0)
            {
                throw reader.Fail($"the BMP {name} mask 0x{mask:X8} uses bits beyond the {bits}-bit pixel");
            }

            if (mask != 0)
            {
                var shifted = mask >> System.Numerics.BitOperations.TrailingZeroCount(mask);
                if ((shifted & (shifted + 1)) != 0)
                {
                    throw reader.Fail($"the BMP {name} mask 0x{mask:X8} is not one run of bits");
                }
            }
        }
    }
}
