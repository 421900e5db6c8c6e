using System.Buffers.Binary;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Tests.Imaging;

/// <summary>Builds BMP files byte by byte, so each test states exactly what the file holds.</summary>
internal sealed record TestBmp
{
    public int Width { get; init; }

    public int Height { get; init; }

    public int BitsPerPixel { get; init; } = 1;

    public bool TopDown { get; init; }

    /// <summary>12 (OS/2 v1), 40, 108 or 124.</summary>
    public int HeaderSize { get; init; } = 40;

    public uint Compression { get; init; }

    public Rgba32[] Palette { get; init; } = [Rgba32.Black, Rgba32.White];

    public uint[]? Masks { get; init; }

    public int PelsPerMetreX { get; init; } = 3780;

    public int PelsPerMetreY { get; init; } = 3780;

    /// <summary>Pixel data exactly as stored (rows already padded and ordered, or RLE codes); null to build it from <see cref="Rows"/>.</summary>
    public byte[]? PixelData { get; init; }

    /// <summary>Rows top to bottom, each packed as BMP packs a row (without padding).</summary>
    public byte[][]? Rows { get; init; }

    /// <summary>Packs palette indices into BMP rows (top to bottom) at <see cref="BitsPerPixel"/>.</summary>
    public static byte[][] PackIndices(int[,] indices, int bits)
    {
        int height = indices.GetLength(0), width = indices.GetLength(1);
        var rows = new byte[height][];
        for (var y = 0; y < height; y++)
        {
            rows[y] = new byte[((width * bits) + 7) / 8];
            for (var x = 0; x < width; x++)
            {
                var shift = 8 - bits - ((x * bits) % 8);
                rows[y][x * bits / 8] |= (byte)(indices[y, x] << shift);
            }
        }

        return rows;
    }

    public byte[] ToBytes()
    {
        var entry = HeaderSize == 12 ? 3 : 4;
        var paletteBytes = BitsPerPixel <= 8 ? Palette.Length * entry : 0;
        var maskBytes = Masks is not null && HeaderSize == 40 ? Masks.Length * 4 : 0;
        var pixels = PixelData ?? BuildPixels();
        var offset = 14 + HeaderSize + maskBytes + paletteBytes;
        var file = new byte[offset + pixels.Length];
        file[0] = (byte)'B';
        file[1] = (byte)'M';
        BinaryPrimitives.WriteUInt32LittleEndian(file.AsSpan(2), (uint)file.Length);
        BinaryPrimitives.WriteUInt32LittleEndian(file.AsSpan(10), (uint)offset);
        var h = file.AsSpan(14, HeaderSize);
        BinaryPrimitives.WriteUInt32LittleEndian(h, (uint)HeaderSize);
        if (HeaderSize == 12)
        {
            BinaryPrimitives.WriteUInt16LittleEndian(h[4..], (ushort)Width);
            BinaryPrimitives.WriteUInt16LittleEndian(h[6..], (ushort)Height);
            BinaryPrimitives.WriteUInt16LittleEndian(h[8..], 1);
            BinaryPrimitives.WriteUInt16LittleEndian(h[10..], (ushort)BitsPerPixel);
        }
        else
        {
            BinaryPrimitives.WriteInt32LittleEndian(h[4..], Width);
            BinaryPrimitives.WriteInt32LittleEndian(h[8..], TopDown ? -Height : Height);
            BinaryPrimitives.WriteUInt16LittleEndian(h[12..], 1);
            BinaryPrimitives.WriteUInt16LittleEndian(h[14..], (ushort)BitsPerPixel);
            BinaryPrimitives.WriteUInt32LittleEndian(h[16..], Compression);
            BinaryPrimitives.WriteUInt32LittleEndian(h[20..], (uint)pixels.Length);
            BinaryPrimitives.WriteInt32LittleEndian(h[24..], PelsPerMetreX);
            BinaryPrimitives.WriteInt32LittleEndian(h[28..], PelsPerMetreY);
            BinaryPrimitives.WriteUInt32LittleEndian(h[32..], BitsPerPixel <= 8 ? (uint)Palette.Length : 0);
            if (Masks is not null && HeaderSize >= 52)
            {
                for (var i = 0; i < Masks.Length; i++)
                {
                    BinaryPrimitives.WriteUInt32LittleEndian(h[(40 + (4 * i))..], Masks[i]);
                }
            }
        }

        var at = 14 + HeaderSize;
        if (maskBytes > 0)
        {
            foreach (var m in Masks!)
            {
                BinaryPrimitives.WriteUInt32LittleEndian(file.AsSpan(at), m);
                at += 4;
            }
        }

        if (paletteBytes > 0)
        {
            foreach (var c in Palette)
            {
                file[at] = c.B;
                file[at + 1] = c.G;
                file[at + 2] = c.R;
                at += entry;
            }
        }

        pixels.CopyTo(file, offset);
        return file;
    }

    private byte[] BuildPixels()
    {
        var stride = ((Width * BitsPerPixel) + 31) / 32 * 4;
        var data = new byte[stride * Height];
        for (var y = 0; y < Height; y++)
        {
            var stored = TopDown ? y : Height - 1 - y;
            Rows![y].CopyTo(data, stored * stride);
        }

        return data;
    }
}
