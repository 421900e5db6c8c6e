using System.Runtime.InteropServices;

namespace LaserEngrave.Core.Imaging;

/// <summary>Decodes BMP run-length encoding: RLE8, RLE4 and OS/2 RLE24, with delta, end-of-line and early end-of-bitmap codes.</summary>
/// <remarks>
/// Pixels the data skips (delta codes, early end of line or bitmap) are left transparent, so they never burn.
/// Every run is checked against the row and the image before it is written; a run that would overflow is an error.
/// </remarks>
internal static class BmpRleDecoder
{
    /// <summary>Decodes an RLE4 or RLE8 image into 8-bit indices, adding a transparent palette entry when pixels were skipped.</summary>
    public static LoadedImage Decode(ImageReader reader, BmpHeader header, ImageInfo info)
    {
        var width = header.Width;
        var height = header.Height;
        var data = ReadData(reader, header);
        if (header.Compression == BmpCompression.Rle24)
        {
            ImageLimits.CheckFullColour(reader.Path, width, height);
            var target = new RgbaTarget(new byte[(long)width * height * 4], width, height, null);
            Run(reader, header, data, ref target);
            return LoadedImage.Rgba(info, width, height, target.Pixels);
        }

        var palette = header.ReadPalette(reader);
        ImageLimits.CheckIndexed(reader.Path, width, height, 8);

        // Skipped pixels get the index one past the palette, which becomes a transparent entry if any are left.
        var full = palette.Length == 256;
        var indices = new byte[(long)width * height];
        if (!full)
        {
            Array.Fill(indices, (byte)palette.Length);
        }

        var indexTarget = new IndexTarget(indices, width, height, palette.Length, reader.Path);
        Run(reader, header, data, ref indexTarget);
        var skipped = indexTarget.Written < (long)width * height;
        if (!skipped)
        {
            return LoadedImage.Indexed(info, width, height, 8, palette, indices);
        }

        if (!full)
        {
            return LoadedImage.Indexed(info, width, height, 8, [.. palette, Rgba32.Transparent], indices);
        }

        // A full palette leaves no spare index, so decode again to RGBA, where untouched pixels stay transparent.
        ImageLimits.CheckFullColour(reader.Path, width, height);
        var rgbaTarget = new RgbaTarget(new byte[(long)width * height * 4], width, height, palette);
        Run(reader, header, data, ref rgbaTarget);
        return LoadedImage.Rgba(info, width, height, rgbaTarget.Pixels);
    }

    private static byte[] ReadData(ImageReader reader, BmpHeader header)
    {
        reader.Position = header.PixelOffset;
        var available = reader.Remaining;
        var size = header.ImageSize > 0 && header.ImageSize <= available ? header.ImageSize : available;
        return reader.ReadBlock(size, "the RLE pixel data");
    }

    private static void Run<TTarget>(ImageReader reader, BmpHeader header, byte[] data, ref TTarget target)
        where TTarget : struct, ITarget
    {
        var width = header.Width;
        var height = header.Height;
        var pixelBytes = header.Compression == BmpCompression.Rle24 ? 3 : 1;
        var four = header.Compression == BmpCompression.Rle4;
        int x = 0, row = 0, pos = 0;
        while (true)
        {
            if (pos + 2 > data.Length)
            {
                if (row >= height)
                {
                    return;
                }

                throw reader.Fail($"the RLE data ends in row {row} of {height} without an end-of-bitmap code (file truncated?)");
            }

            int count = data[pos];
            if (count > 0)
            {
                if (pos + 1 + pixelBytes > data.Length)
                {
                    throw reader.Fail("the RLE data is truncated inside a run");
                }

                CheckRun(reader, x, row, count, width, height);
                if (pixelBytes == 3)
                {
                    target.Fill(row, x, count, BmpBitFields.PackBgr(data[pos + 1], data[pos + 2], data[pos + 3]));
                }
                else if (four)
                {
                    var pair = data[pos + 1];
                    for (var i = 0; i < count; i++)
                    {
                        target.Set(row, x + i, (uint)((i & 1) == 0 ? pair >> 4 : pair & 0xF));
                    }
                }
                else
                {
                    target.Fill(row, x, count, data[pos + 1]);
                }

                x += count;
                pos += 1 + pixelBytes;
                continue;
            }

            var code = data[pos + 1];
            pos += 2;
            switch (code)
            {
                case 0:
                    x = 0;
                    row++;
                    break;
                case 1:
                    return;
                case 2:
                    if (pos + 2 > data.Length)
                    {
                        throw reader.Fail("the RLE data is truncated inside a delta code");
                    }

                    x += data[pos];
                    row += data[pos + 1];
                    pos += 2;
                    if (x > width || row > height)
                    {
                        throw reader.Fail($"an RLE delta code moves to ({x}, {row}), outside the {width} x {height} image");
                    }

                    break;
                default:
                    int literal = code;
                    var bytes = four ? (literal + 1) / 2 : literal * pixelBytes;
                    if (pos + bytes > data.Length)
                    {
                        throw reader.Fail("the RLE data is truncated inside a literal run");
                    }

                    CheckRun(reader, x, row, literal, width, height);
                    for (var i = 0; i < literal; i++)
                    {
                        uint value = pixelBytes == 3
                            ? BmpBitFields.PackBgr(data[pos + (3 * i)], data[pos + (3 * i) + 1], data[pos + (3 * i) + 2])
                            : four
                                ? (uint)((i & 1) == 0 ? data[pos + (i >> 1)] >> 4 : data[pos + (i >> 1)] & 0xF)
                                : data[pos + i];
                        target.Set(row, x + i, value);
                    }

                    x += literal;
                    pos += (bytes + 1) & ~1;
                    break;
            }
        }
    }

    private static void CheckRun(ImageReader reader, int x, int row, int count, int width, int height)
    {
        if (row >= height)
        {
            throw reader.Fail($"the RLE data writes past the last of {height} rows");
        }

        if (x + count > width)
        {
            throw reader.Fail($"an RLE run of {count} pixels at column {x} of row {row} passes the end of the {width}-pixel row");
        }
    }

    private interface ITarget
    {
        void Set(int row, int x, uint value);

        void Fill(int row, int x, int count, uint value);
    }

    /// <summary>Writes 8-bit indices; RLE rows count from the bottom.</summary>
    private struct IndexTarget(byte[] indices, int width, int height, int paletteCount, string path) : ITarget
    {
        public long Written { get; private set; }

        public void Set(int row, int x, uint value) => Fill(row, x, 1, value);

        public void Fill(int row, int x, int count, uint value)
        {
            if (value >= paletteCount)
            {
                throw new ImageLoadException(path, $"pixel ({x}, {height - 1 - row}) uses colour index {value}, but the palette has only {paletteCount} colours");
            }

            indices.AsSpan((int)(((long)(height - 1 - row) * width) + x), count).Fill((byte)value);
            Written += count;
        }
    }

    /// <summary>Writes RGBA, through the palette when there is one.</summary>
    private readonly struct RgbaTarget(byte[] pixels, int width, int height, Rgba32[]? palette) : ITarget
    {
        public byte[] Pixels => pixels;

        public void Set(int row, int x, uint value) => Fill(row, x, 1, value);

        public void Fill(int row, int x, int count, uint value)
        {
            if (palette is not null)
            {
                var c = palette[(int)value];
                value = BmpBitFields.PackBgr(c.B, c.G, c.R);
            }

            MemoryMarshal.Cast<byte, uint>(pixels.AsSpan()).Slice((int)(((long)(height - 1 - row) * width) + x), count).Fill(value);
        }
    }
}
