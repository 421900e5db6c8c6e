using System.Buffers.Binary;
using System.IO.Compression;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Tests.Imaging;

/// <summary>Encodes PNG files for tests with every colour type, depth, filter and Adam7, so decoding can be checked against known samples.</summary>
internal sealed record TestPng
{
    public int Width { get; init; }

    public int Height { get; init; }

    public int ColourType { get; init; }

    public int BitDepth { get; init; } = 8;

    /// <summary>Samples per pixel in channel order (grey; RGB; index; grey, alpha; RGBA), row-major, at the bit depth.</summary>
    public required int[] Samples { get; init; }

    public byte[]? Palette { get; init; }

    public byte[]? Transparency { get; init; }

    public bool Interlaced { get; init; }

    public (uint X, uint Y, byte Unit)? Physical { get; init; }

    /// <summary>Split the compressed data into IDAT chunks of this size.</summary>
    public int IdatChunkSize { get; init; } = 1 << 20;

    private int Channels => ColourType switch
    {
        0 or 3 => 1,
        2 => 3,
        4 => 2,
        _ => 4,
    };

    public byte[] ToBytes()
    {
        using var file = new MemoryStream();
        file.Write([0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A]);
        var ihdr = new byte[13];
        BinaryPrimitives.WriteInt32BigEndian(ihdr, Width);
        BinaryPrimitives.WriteInt32BigEndian(ihdr.AsSpan(4), Height);
        ihdr[8] = (byte)BitDepth;
        ihdr[9] = (byte)ColourType;
        ihdr[12] = Interlaced ? (byte)1 : (byte)0;
        WriteChunk(file, "IHDR", ihdr);
        if (Physical is { } p)
        {
            var phys = new byte[9];
            BinaryPrimitives.WriteUInt32BigEndian(phys, p.X);
            BinaryPrimitives.WriteUInt32BigEndian(phys.AsSpan(4), p.Y);
            phys[8] = p.Unit;
            WriteChunk(file, "pHYs", phys);
        }

        if (Palette is not null)
        {
            WriteChunk(file, "PLTE", Palette);
        }

        if (Transparency is not null)
        {
            WriteChunk(file, "tRNS", Transparency);
        }

        var compressed = Compress(RawData());
        for (var at = 0; at < compressed.Length; at += IdatChunkSize)
        {
            WriteChunk(file, "IDAT", compressed.AsSpan(at, Math.Min(IdatChunkSize, compressed.Length - at)));
        }

        WriteChunk(file, "IEND", []);
        return file.ToArray();
    }

    public static void WriteChunk(Stream output, string type, ReadOnlySpan<byte> data)
    {
        var header = new byte[8];
        BinaryPrimitives.WriteInt32BigEndian(header, data.Length);
        System.Text.Encoding.ASCII.GetBytes(type, header.AsSpan(4));
        output.Write(header);
        output.Write(data);
        var crc = new byte[4];
        var body = header.AsSpan(4).ToArray().Concat(data.ToArray()).ToArray();
        BinaryPrimitives.WriteUInt32BigEndian(crc, Crc32.Compute(body));
        output.Write(crc);
    }

    public static byte[] Compress(byte[] raw)
    {
        using var compressed = new MemoryStream();
        using (var zlib = new ZLibStream(compressed, CompressionLevel.Optimal, leaveOpen: true))
        {
            zlib.Write(raw);
        }

        return compressed.ToArray();
    }

    /// <summary>The filtered scanlines; each row uses filter (row number mod 5) so all five filters get decoded.</summary>
    private byte[] RawData()
    {
        var output = new MemoryStream();
        (int X, int Y, int DX, int DY)[] passes = Interlaced
            ? [(0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4), (1, 0, 2, 2), (0, 1, 1, 2)]
            : [(0, 0, 1, 1)];
        var bitsPerPixel = Channels * BitDepth;
        var step = Math.Max(1, bitsPerPixel / 8);
        var rowNumber = 0;
        foreach (var (x0, y0, dx, dy) in passes)
        {
            var w = (Width - x0 + dx - 1) / dx;
            var h = (Height - y0 + dy - 1) / dy;
            if (w <= 0 || h <= 0)
            {
                continue;
            }

            var rowBytes = ((w * bitsPerPixel) + 7) / 8;
            var previous = new byte[rowBytes];
            for (var j = 0; j < h; j++)
            {
                var row = new byte[rowBytes];
                var bit = 0;
                for (var i = 0; i < w; i++)
                {
                    var pixel = ((y0 + (j * dy)) * Width) + x0 + (i * dx);
                    for (var c = 0; c < Channels; c++)
                    {
                        var v = Samples[(pixel * Channels) + c];
                        if (BitDepth == 16)
                        {
                            row[bit / 8] = (byte)(v >> 8);
                            row[(bit / 8) + 1] = (byte)v;
                        }
                        else
                        {
                            row[bit / 8] |= (byte)(v << (8 - BitDepth - (bit % 8)));
                        }

                        bit += BitDepth;
                    }
                }

                var filter = (byte)(rowNumber++ % 5);
                output.WriteByte(filter);
                output.Write(Filter(filter, row, previous, step));
                previous = row;
            }
        }

        return output.ToArray();
    }

    private static byte[] Filter(byte filter, byte[] row, byte[] previous, int step)
    {
        var result = new byte[row.Length];
        for (var i = 0; i < row.Length; i++)
        {
            int a = i >= step ? row[i - step] : 0, b = previous[i], c = i >= step ? previous[i - step] : 0;
            var predictor = filter switch
            {
                1 => a,
                2 => b,
                3 => (a + b) / 2,
                4 => Paeth(a, b, c),
                _ => 0,
            };
            result[i] = (byte)(row[i] - predictor);
        }

        return result;
    }

    private static int Paeth(int a, int b, int c)
    {
        int p = a + b - c, pa = Math.Abs(p - a), pb = Math.Abs(p - b), pc = Math.Abs(p - c);
        return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
    }
}
