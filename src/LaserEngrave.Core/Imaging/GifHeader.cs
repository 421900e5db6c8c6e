using System.Buffers.Binary;

namespace LaserEngrave.Core.Imaging;

/// <summary>A GIF's logical screen, colour tables, and the first frame's descriptor and transparency.</summary>
internal sealed record GifHeader
{
    public required int ScreenWidth { get; init; }

    public required int ScreenHeight { get; init; }

    public required int Left { get; init; }

    public required int Top { get; init; }

    public required int FrameWidth { get; init; }

    public required int FrameHeight { get; init; }

    public required bool Interlaced { get; init; }

    /// <summary>The local colour table, else the global one; opaque.</summary>
    public required Rgba32[] Palette { get; init; }

    /// <summary>The graphic control extension's transparent index, or -1.</summary>
    public required int TransparentIndex { get; init; }

    /// <summary>File offset of the LZW minimum code size byte.</summary>
    public required long DataOffset { get; init; }

    /// <summary>The canvas: the logical screen, grown to hold the frame if the frame sticks out.</summary>
    public int CanvasWidth => Math.Max(ScreenWidth, Left + FrameWidth);

    public int CanvasHeight => Math.Max(ScreenHeight, Top + FrameHeight);

    public bool FrameCoversCanvas => Left == 0 && Top == 0 && FrameWidth == CanvasWidth && FrameHeight == CanvasHeight;

    public ImageInfo ToInfo(string path, long fileSize) => new(
        path,
        ImageFormat.Gif,
        System.Numerics.BitOperations.Log2((uint)Palette.Length),
        Palette.Length,
        CanvasWidth,
        CanvasHeight,
        fileSize,
        null,
        null,
        RowOrder.TopDown,
        "LZW",
        TransparentIndex >= 0 || !FrameCoversCanvas,
        Interlaced);

    public static GifHeader Read(ImageReader reader)
    {
        reader.Position = 0;
        Span<byte> head = stackalloc byte[13];
        reader.ReadExactly(head, "the GIF header");
        if (!head.StartsWith("GIF87a"u8) && !head.StartsWith("GIF89a"u8))
        {
            throw reader.Fail("not a GIF file (bad signature)");
        }

        int screenWidth = BinaryPrimitives.ReadUInt16LittleEndian(head[6..]), screenHeight = BinaryPrimitives.ReadUInt16LittleEndian(head[8..]);
        var global = (head[10] & 0x80) != 0 ? ReadColourTable(reader, head[10] & 7, "the GIF global colour table") : null;
        var transparent = -1;
        Span<byte> descriptor = stackalloc byte[9];
        while (true)
        {
            var block = reader.ReadByte("the GIF block list");
            switch (block)
            {
                case 0x21:
                    var label = reader.ReadByte("a GIF extension");
                    if (label == 0xF9)
                    {
                        var size = reader.ReadByte("a GIF graphic control extension");
                        var control = reader.ReadBlock(size, "a GIF graphic control extension");
                        if (size >= 4)
                        {
                            transparent = (control[0] & 1) != 0 ? control[3] : -1;
                        }
                    }

                    SkipSubBlocks(reader);
                    break;
                case 0x2C:
                    reader.ReadExactly(descriptor, "the GIF image descriptor");
                    int left = BinaryPrimitives.ReadUInt16LittleEndian(descriptor), top = BinaryPrimitives.ReadUInt16LittleEndian(descriptor[2..]);
                    int width = BinaryPrimitives.ReadUInt16LittleEndian(descriptor[4..]), height = BinaryPrimitives.ReadUInt16LittleEndian(descriptor[6..]);
                    var flags = descriptor[8];
                    var local = (flags & 0x80) != 0 ? ReadColourTable(reader, flags & 7, "the GIF local colour table") : null;
                    var palette = local ?? global ?? throw reader.Fail("the GIF has neither a global nor a local colour table");
                    if (width == 0 || height == 0)
                    {
                        throw reader.Fail($"the first GIF frame is {width} x {height} pixels");
                    }

                    var header = new GifHeader
                    {
                        ScreenWidth = screenWidth,
                        ScreenHeight = screenHeight,
                        Left = left,
                        Top = top,
                        FrameWidth = width,
                        FrameHeight = height,
                        Interlaced = (flags & 0x40) != 0,
                        Palette = palette,
                        TransparentIndex = transparent < palette.Length ? transparent : -1,
                        DataOffset = reader.Position,
                    };
                    ImageLimits.CheckDimensions(reader.Path, header.CanvasWidth, header.CanvasHeight);
                    return header;
                case 0x3B:
                    throw reader.Fail("the GIF contains no image");
                default:
                    throw reader.Fail($"the GIF is corrupt: unknown block type 0x{block:X2} at offset {reader.Position - 1}");
            }
        }
    }

    /// <summary>Skips a chain of data sub-blocks and returns their total payload.</summary>
    public static long SkipSubBlocks(ImageReader reader)
    {
        long total = 0;
        while (true)
        {
            var size = reader.ReadByte("GIF data sub-blocks");
            if (size == 0)
            {
                return total;
            }

            reader.Skip(size, "a GIF data sub-block");
            total += size;
        }
    }

    private static Rgba32[] ReadColourTable(ImageReader reader, int sizeBits, string what)
    {
        var count = 2 << sizeBits;
        var raw = reader.ReadBlock(count * 3, what);
        var table = new Rgba32[count];
        for (var i = 0; i < count; i++)
        {
            table[i] = new Rgba32(raw[3 * i], raw[(3 * i) + 1], raw[(3 * i) + 2]);
        }

        return table;
    }
}
