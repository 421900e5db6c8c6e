using System.Buffers.Binary;

namespace LaserEngrave.Core.Imaging;

/// <summary>What a PNG's chunks before the image data say: IHDR, PLTE, tRNS, pHYs, and where the image data is.</summary>
internal sealed record PngHeader
{
    private static readonly byte[] Signature = [0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A];

    public required int Width { get; init; }

    public required int Height { get; init; }

    public required int BitDepth { get; init; }

    /// <summary>0 grey, 2 RGB, 3 palette, 4 grey + alpha, 6 RGBA.</summary>
    public required int ColourType { get; init; }

    public required bool Interlaced { get; init; }

    /// <summary>The PLTE colours with the tRNS alphas applied; empty when there is no PLTE.</summary>
    public required Rgba32[] Palette { get; init; }

    /// <summary>The raw tRNS chunk, or null.</summary>
    public required byte[]? Transparency { get; init; }

    public required long PixelsPerUnitX { get; init; }

    public required long PixelsPerUnitY { get; init; }

    /// <summary>Whether pHYs counts pixels per metre (unit 1) rather than only giving the aspect ratio.</summary>
    public required bool UnitIsMetre { get; init; }

    /// <summary>File offset of the first IDAT chunk's length field.</summary>
    public required long FirstIdatOffset { get; init; }

    /// <summary>Total IDAT payload, known only after a whole-file scan; 0 otherwise.</summary>
    public required long IdatBytes { get; init; }

    public int Channels => ColourType switch
    {
        0 or 3 => 1,
        2 => 3,
        4 => 2,
        _ => 4,
    };

    public int BitsPerPixel => Channels * BitDepth;

    public bool HasAlpha => ColourType is 4 or 6 || Transparency is not null;

    /// <summary>The tRNS grey sample of a grey image, or -1.</summary>
    public int TransparentGrey => ColourType == 0 && Transparency is { Length: >= 2 } t ? BinaryPrimitives.ReadUInt16BigEndian(t) : -1;

    public ImageInfo ToInfo(string path, long fileSize) => new(
        path,
        ImageFormat.Png,
        BitsPerPixel,
        Palette.Length,
        Width,
        Height,
        fileSize,
        UnitIsMetre ? ImageInfo.DpiFromPixelsPerMetre(PixelsPerUnitX) : null,
        UnitIsMetre ? ImageInfo.DpiFromPixelsPerMetre(PixelsPerUnitY) : null,
        RowOrder.TopDown,
        "deflate",
        HasAlpha,
        Interlaced);

    /// <summary>Reads the chunks from <paramref name="start"/> up to the first IDAT, or through the whole file to total the IDAT bytes.</summary>
    public static PngHeader Read(ImageReader reader, long start, bool wholeFile)
    {
        reader.Position = start;
        Span<byte> signature = stackalloc byte[8];
        reader.ReadExactly(signature, "the PNG signature");
        if (!signature.SequenceEqual(Signature))
        {
            throw reader.Fail("not a PNG file (bad signature)");
        }

        int width = 0, height = 0, depth = 0, colourType = 0;
        var interlaced = false;
        var seenHeader = false;
        byte[]? plte = null, trns = null;
        long ppuX = 0, ppuY = 0;
        var metre = false;
        long firstIdat = -1, idatBytes = 0;
        Span<byte> chunkHeader = stackalloc byte[8];
        while (reader.Remaining > 0)
        {
            var chunkStart = reader.Position;
            reader.ReadExactly(chunkHeader, "a PNG chunk header");
            var length = BinaryPrimitives.ReadUInt32BigEndian(chunkHeader);
            var type = chunkHeader[4..8];
            var name = System.Text.Encoding.ASCII.GetString(type);
            if (!IsChunkName(type))
            {
                throw reader.Fail($"the PNG is corrupt: bytes at offset {chunkStart + 4} are not a chunk name");
            }

            if (length > int.MaxValue || length + 4 > reader.Remaining)
            {
                throw reader.Fail($"the file is truncated: PNG chunk {name} at offset {chunkStart} claims {length} bytes, but only {reader.Remaining} remain");
            }

            if (!seenHeader && name != "IHDR")
            {
                throw reader.Fail($"the PNG is corrupt: the first chunk is {name}, not IHDR");
            }

            switch (name)
            {
                case "IHDR":
                    var ihdr = ReadChunk(reader, type, length, 13, name);
                    width = BinaryPrimitives.ReadInt32BigEndian(ihdr);
                    height = BinaryPrimitives.ReadInt32BigEndian(ihdr.AsSpan(4));
                    depth = ihdr[8];
                    colourType = ihdr[9];
                    if (ihdr[10] != 0 || ihdr[11] != 0 || ihdr[12] > 1)
                    {
                        throw reader.Fail($"the PNG uses compression {ihdr[10]}, filter method {ihdr[11]} or interlace {ihdr[12]}, which PNG does not define");
                    }

                    interlaced = ihdr[12] == 1;
                    CheckDepth(reader, colourType, depth);
                    ImageLimits.CheckDimensions(reader.Path, width, height);
                    seenHeader = true;
                    break;
                case "PLTE" when firstIdat < 0:
                    if (length % 3 != 0 || length == 0 || length > 768)
                    {
                        throw reader.Fail($"the PNG palette has {length} bytes; it must be 3 to 768 and a multiple of 3");
                    }

                    plte = ReadChunk(reader, type, length, length, name);
                    break;
                case "tRNS" when firstIdat < 0:
                    trns = ReadChunk(reader, type, length, length, name);
                    break;
                case "pHYs" when firstIdat < 0:
                    var phys = ReadChunk(reader, type, length, 9, name);
                    ppuX = BinaryPrimitives.ReadUInt32BigEndian(phys);
                    ppuY = BinaryPrimitives.ReadUInt32BigEndian(phys.AsSpan(4));
                    metre = phys[8] == 1;
                    break;
                case "IDAT":
                    if (firstIdat < 0)
                    {
                        firstIdat = chunkStart;
                        if (!wholeFile)
                        {
                            return Build();
                        }
                    }

                    idatBytes += length;
                    reader.Skip(length + 4, "a PNG chunk");
                    break;
                case "IEND":
                    return Build();
                default:
                    if ((type[0] & 0x20) == 0 && name is not ("PLTE" or "tRNS" or "pHYs"))
                    {
                        throw reader.Fail($"the PNG has a critical chunk {name} this decoder does not know");
                    }

                    reader.Skip(length + 4, "a PNG chunk");
                    break;
            }
        }

        return Build();

        PngHeader Build()
        {
            if (!seenHeader)
            {
                throw reader.Fail("the file is truncated: the PNG has no IHDR chunk");
            }

            if (firstIdat < 0)
            {
                throw reader.Fail("the PNG has no image data (IDAT chunk)");
            }

            if (colourType == 3 && plte is null)
            {
                throw reader.Fail("the PNG is a palette image without a palette (PLTE chunk)");
            }

            var palette = new Rgba32[plte is null ? 0 : plte.Length / 3];
            for (var i = 0; i < palette.Length; i++)
            {
                var alpha = colourType == 3 && trns is not null && i < trns.Length ? trns[i] : (byte)255;
                palette[i] = new Rgba32(plte![3 * i], plte[(3 * i) + 1], plte[(3 * i) + 2], alpha);
            }

            var transparency = colourType switch
            {
                0 when trns is { Length: >= 2 } => trns,
                2 when trns is { Length: >= 6 } => trns,
                3 when trns is { Length: > 0 } => trns,
                _ => null,
            };

            return new PngHeader
            {
                Width = width,
                Height = height,
                BitDepth = depth,
                ColourType = colourType,
                Interlaced = interlaced,
                Palette = colourType is 3 ? palette : [],
                Transparency = transparency,
                PixelsPerUnitX = ppuX,
                PixelsPerUnitY = ppuY,
                UnitIsMetre = metre,
                FirstIdatOffset = firstIdat,
                IdatBytes = idatBytes,
            };
        }
    }

    private static byte[] ReadChunk(ImageReader reader, ReadOnlySpan<byte> type, uint length, uint expected, string name)
    {
        if (length != expected)
        {
            throw reader.Fail($"the PNG chunk {name} has {length} bytes; it must have {expected}");
        }

        var data = reader.ReadBlock(length, $"the PNG chunk {name}");
        Span<byte> crc = stackalloc byte[4];
        reader.ReadExactly(crc, $"the CRC of the PNG chunk {name}");
        var actual = Crc32.Finish(Crc32.Update(Crc32.Update(Crc32.Start, type), data));
        if (actual != BinaryPrimitives.ReadUInt32BigEndian(crc))
        {
            throw reader.Fail($"the PNG chunk {name} fails its CRC check (the file is corrupt)");
        }

        return data;
    }

    private static void CheckDepth(ImageReader reader, int colourType, int depth)
    {
        var valid = colourType switch
        {
            0 => depth is 1 or 2 or 4 or 8 or 16,
            3 => depth is 1 or 2 or 4 or 8,
            2 or 4 or 6 => depth is 8 or 16,
            _ => throw reader.Fail($"PNG colour type {colourType} does not exist"),
        };
        if (!valid)
        {
            throw reader.Fail($"PNG colour type {colourType} cannot have {depth} bits per sample");
        }
    }

    private static bool IsChunkName(ReadOnlySpan<byte> type)
    {
        foreach (var b in type)
        {
            if (b is not ((>= (byte)'A' and <= (byte)'Z') or (>= (byte)'a' and <= (byte)'z')))
            {
                return false;
            }
        }

        return true;
    }
}
