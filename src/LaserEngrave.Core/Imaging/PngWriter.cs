using System.Buffers.Binary;
using System.IO.Compression;

namespace LaserEngrave.Core.Imaging;

/// <summary>Writes 8-bit grey or RGBA PNG files.</summary>
/// <remarks>
/// Written by hand because SixLabors.ImageSharp is not on this machine's package source (docs/dependencies.md);
/// the framework's ZLibStream does the compression, so only the chunk layout lives here.
/// </remarks>
public static class PngWriter
{
    private static readonly byte[] Signature = [0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A];

    /// <summary>Writes an RGBA image: 4 bytes per pixel, rows top to bottom.</summary>
    public static void WriteRgba(Stream output, int width, int height, ReadOnlySpan<byte> rgba) =>
        Write(output, width, height, rgba, colourType: 6, bytesPerPixel: 4);

    /// <summary>Writes a greyscale image: 1 byte per pixel, rows top to bottom.</summary>
    public static void WriteGray(Stream output, int width, int height, ReadOnlySpan<byte> gray) =>
        Write(output, width, height, gray, colourType: 0, bytesPerPixel: 1);

    /// <summary>Writes a mask as black (burn) on white.</summary>
    public static void WriteMask(Stream output, BitMask mask)
    {
        ArgumentNullException.ThrowIfNull(mask);
        var gray = new byte[(long)mask.Width * mask.Height];
        for (var y = 0; y < mask.Height; y++)
        {
            var row = gray.AsSpan(y * mask.Width, mask.Width);
            var words = mask.ReadRow(y);
            for (var x = 0; x < mask.Width; x++)
            {
                row[x] = (words[x >> 6] >> (x & 63) & 1) != 0 ? (byte)0 : (byte)255;
            }
        }

        WriteGray(output, mask.Width, mask.Height, gray);
    }

    public static void WriteMask(string path, BitMask mask)
    {
        using var file = File.Create(path);
        WriteMask(file, mask);
    }

    private static void Write(Stream output, int width, int height, ReadOnlySpan<byte> pixels, byte colourType, int bytesPerPixel)
    {
        ArgumentNullException.ThrowIfNull(output);
        var stride = width * bytesPerPixel;
        if (pixels.Length < (long)stride * height)
        {
            throw new ArgumentException($"{pixels.Length} bytes is too few for {width} x {height} pixels", nameof(pixels));
        }

        output.Write(Signature);
        Span<byte> header = stackalloc byte[13];
        BinaryPrimitives.WriteInt32BigEndian(header, width);
        BinaryPrimitives.WriteInt32BigEndian(header[4..], height);
        header[8] = 8;
        header[9] = colourType;
        header[10] = 0;
        header[11] = 0;
        header[12] = 0;
        WriteChunk(output, "IHDR"u8, header);

        using var compressed = new MemoryStream();
        using (var zlib = new ZLibStream(compressed, CompressionLevel.Fastest, leaveOpen: true))
        {
            for (var y = 0; y < height; y++)
            {
                zlib.WriteByte(0);
                zlib.Write(pixels.Slice(y * stride, stride));
            }
        }

        WriteChunk(output, "IDAT"u8, compressed.GetBuffer().AsSpan(0, (int)compressed.Length));
        WriteChunk(output, "IEND"u8, []);
    }

    private static void WriteChunk(Stream output, ReadOnlySpan<byte> type, ReadOnlySpan<byte> data)
    {
        Span<byte> buffer = stackalloc byte[4];
        BinaryPrimitives.WriteInt32BigEndian(buffer, data.Length);
        output.Write(buffer);
        output.Write(type);
        output.Write(data);
        var crc = Crc32.Start;
        crc = Crc32.Update(crc, type);
        crc = Crc32.Update(crc, data);
        BinaryPrimitives.WriteUInt32BigEndian(buffer, Crc32.Finish(crc));
        output.Write(buffer);
    }
}
