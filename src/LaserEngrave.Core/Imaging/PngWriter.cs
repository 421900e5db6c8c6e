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

    /// <summary>The most pixels a scaled mask may have (256 MB of grey), so a scale cannot exhaust the memory.</summary>
    public const long MaxScaledPixels = 1L << 28;

    /// <summary>Writes a mask as black (burn) on white, each mask pixel as <paramref name="scale"/> x <paramref name="scale"/> image pixels.</summary>
    /// <exception cref="ArgumentOutOfRangeException">The scale is below 1 or makes more than <see cref="MaxScaledPixels"/> pixels.</exception>
    public static void WriteMask(Stream output, BitMask mask, int scale = 1)
    {
        ArgumentNullException.ThrowIfNull(mask);
        ArgumentOutOfRangeException.ThrowIfLessThan(scale, 1);
        if (ScaledPixels(mask.Width, mask.Height, scale) > MaxScaledPixels)
        {
            throw new ArgumentOutOfRangeException(nameof(scale), scale, $"{mask.Width} x {mask.Height} pixels at {scale} x {scale} is more than {MaxScaledPixels} pixels");
        }

        var width = mask.Width * scale;
        var gray = new byte[(long)width * mask.Height * scale];
        for (var y = 0; y < mask.Height; y++)
        {
            var row = gray.AsSpan(y * scale * width, width);
            var words = mask.ReadRow(y);
            for (var x = 0; x < mask.Width; x++)
            {
                row.Slice(x * scale, scale).Fill((words[x >> 6] >> (x & 63) & 1) != 0 ? (byte)0 : (byte)255);
            }

            for (var copy = 1; copy < scale; copy++)
            {
                row.CopyTo(gray.AsSpan((y * scale + copy) * width, width));
            }
        }

        WriteGray(output, width, mask.Height * scale, gray);
    }

    /// <inheritdoc cref="WriteMask(Stream, BitMask, int)"/>
    public static void WriteMask(string path, BitMask mask, int scale = 1)
    {
        using var file = File.Create(path);
        WriteMask(file, mask, scale);
    }

    /// <summary>How many pixels an image of <paramref name="width"/> x <paramref name="height"/> has at <paramref name="scale"/>.</summary>
    public static long ScaledPixels(int width, int height, int scale) => (long)width * scale * height * scale;

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
