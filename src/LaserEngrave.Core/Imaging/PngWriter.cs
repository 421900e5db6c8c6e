using System.Buffers.Binary;
using System.IO.Compression;

namespace LaserEngrave.Core.Imaging;

/// <summary>Writes 8-bit grey or RGBA PNG files, and masks as 1-bit grey.</summary>
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

    /// <summary>The most pixels a scaled mask may have (a scale only magnifies for looking at, so it may not fill the disk).</summary>
    public const long MaxScaledPixels = 1L << 28;

    /// <summary>How many pixels an image of <paramref name="width"/> x <paramref name="height"/> has at <paramref name="scale"/>.</summary>
    public static long ScaledPixels(int width, int height, int scale) => (long)width * scale * height * scale;

    /// <summary>
    /// Writes a mask as black (burn) on white: a 1-bit greyscale PNG, compressed row by row, each mask pixel as
    /// <paramref name="scale"/> x <paramref name="scale"/> image pixels.
    /// </summary>
    /// <remarks>
    /// Streamed a row at a time into IDAT chunks of at most <see cref="IdatChunkBytes"/>, so a mask of any size the
    /// loader takes (60000 x 60000 pixels: 450 MB as bits) is written without a second copy of it in memory.
    /// </remarks>
    /// <exception cref="ArgumentOutOfRangeException">The scale is below 1, or above 1 and makes more than <see cref="MaxScaledPixels"/> pixels.</exception>
    public static void WriteMask(Stream output, BitMask mask, int scale = 1)
    {
        ArgumentNullException.ThrowIfNull(output);
        ArgumentNullException.ThrowIfNull(mask);
        ArgumentOutOfRangeException.ThrowIfLessThan(scale, 1);
        if (scale > 1 && ScaledPixels(mask.Width, mask.Height, scale) > MaxScaledPixels)
        {
            throw new ArgumentOutOfRangeException(nameof(scale), scale, $"{mask.Width} x {mask.Height} pixels at {scale} x {scale} is more than {MaxScaledPixels} pixels");
        }

        var width = mask.Width * scale;
        WriteHeader(output, width, mask.Height * scale, bitDepth: 1, colourType: 0);
        var row = new byte[1 + ((width + 7) / 8)];
        using (var idat = new ChunkStream(output, IdatChunkBytes))
        {
            using (var zlib = new ZLibStream(idat, CompressionLevel.Fastest, leaveOpen: true))
            {
                for (var y = 0; y < mask.Height; y++)
                {
                    var words = mask.ReadRow(y);
                    if (scale > 1)
                    {
                        WriteScaledRow(row, words, mask.Width, scale);
                        for (var copy = 0; copy < scale; copy++)
                        {
                            zlib.Write(row);
                        }

                        continue;
                    }

                    for (var i = 1; i < row.Length; i++)
                    {
                        // Eight pixels from the mask's word (first pixel in the lowest bit) to PNG's order (first pixel
                        // in the highest bit), burn = black = 0; the padding past the width reads as white.
                        var x = (i - 1) * 8;
                        var bits = (byte)(words[x >> 6] >> (x & 63));
                        var keep = mask.Width - x >= 8 ? 0xFF : (0xFF << (8 - (mask.Width - x))) & 0xFF;
                        row[i] = (byte)(~ReverseBits(bits) & 0xFF | ~keep & 0xFF);
                    }

                    zlib.Write(row);
                }
            }
        }

        WriteChunk(output, "IEND"u8, []);
    }

    /// <summary>Writes the mask to <paramref name="path"/> through a temporary file beside it, so a failure leaves no partial or empty file.</summary>
    public static void WriteMask(string path, BitMask mask, int scale = 1)
    {
        ArgumentException.ThrowIfNullOrEmpty(path);
        var full = Path.GetFullPath(path);
        var temporary = Path.Combine(Path.GetDirectoryName(full) ?? ".", $".{Path.GetFileName(full)}.{Environment.ProcessId}.tmp");
        try
        {
            using (var file = File.Create(temporary))
            {
                WriteMask(file, mask, scale);
            }

            File.Move(temporary, full, overwrite: true);
        }
        finally
        {
            File.Delete(temporary);
        }
    }

    private const int IdatChunkBytes = 1 << 16;

    /// <summary>One PNG row (filter byte 0, then 1-bit pixels, first in the highest bit) of a mask row magnified by <paramref name="scale"/>.</summary>
    private static void WriteScaledRow(byte[] row, ReadOnlySpan<ulong> words, int maskWidth, int scale)
    {
        // Start from white (1 bits), padding included, and clear the bits of every burned pixel's copies.
        Array.Fill(row, (byte)0xFF);
        row[0] = 0;
        for (var x = 0; x < maskWidth; x++)
        {
            if ((words[x >> 6] >> (x & 63) & 1) == 0)
            {
                continue;
            }

            for (var p = x * scale; p < (x + 1) * scale; p++)
            {
                row[1 + (p >> 3)] &= (byte)~(0x80 >> (p & 7));
            }
        }
    }

    private static byte ReverseBits(byte b)
    {
        b = (byte)(((b & 0xF0) >> 4) | ((b & 0x0F) << 4));
        b = (byte)(((b & 0xCC) >> 2) | ((b & 0x33) << 2));
        return (byte)(((b & 0xAA) >> 1) | ((b & 0x55) << 1));
    }

    private static void WriteHeader(Stream output, int width, int height, byte bitDepth, byte colourType)
    {
        output.Write(Signature);
        Span<byte> header = stackalloc byte[13];
        BinaryPrimitives.WriteInt32BigEndian(header, width);
        BinaryPrimitives.WriteInt32BigEndian(header[4..], height);
        header[8] = bitDepth;
        header[9] = colourType;
        header[10] = 0;
        header[11] = 0;
        header[12] = 0;
        WriteChunk(output, "IHDR"u8, header);
    }

    private static void Write(Stream output, int width, int height, ReadOnlySpan<byte> pixels, byte colourType, int bytesPerPixel)
    {
        ArgumentNullException.ThrowIfNull(output);
        var stride = width * bytesPerPixel;
        if (pixels.Length < (long)stride * height)
        {
            throw new ArgumentException($"{pixels.Length} bytes is too few for {width} x {height} pixels", nameof(pixels));
        }

        WriteHeader(output, width, height, bitDepth: 8, colourType);

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

    /// <summary>Cuts what is written to it into PNG chunks of one type (IDAT), each at most a given length.</summary>
    private sealed class ChunkStream(Stream output, int chunkBytes) : Stream
    {
        private readonly byte[] _buffer = new byte[chunkBytes];
        private int _length;

        public override bool CanRead => false;

        public override bool CanSeek => false;

        public override bool CanWrite => true;

        public override long Length => throw new NotSupportedException();

        public override long Position { get => throw new NotSupportedException(); set => throw new NotSupportedException(); }

        public override void Write(byte[] buffer, int offset, int count) => Write(buffer.AsSpan(offset, count));

        public override void Write(ReadOnlySpan<byte> buffer)
        {
            while (buffer.Length > 0)
            {
                var n = Math.Min(buffer.Length, _buffer.Length - _length);
                buffer[..n].CopyTo(_buffer.AsSpan(_length));
                _length += n;
                buffer = buffer[n..];
                if (_length == _buffer.Length)
                {
                    Flush();
                }
            }
        }

        public override void Flush()
        {
            if (_length > 0)
            {
                WriteChunk(output, "IDAT"u8, _buffer.AsSpan(0, _length));
                _length = 0;
            }
        }

        public override int Read(byte[] buffer, int offset, int count) => throw new NotSupportedException();

        public override long Seek(long offset, SeekOrigin origin) => throw new NotSupportedException();

        public override void SetLength(long value) => throw new NotSupportedException();

        protected override void Dispose(bool disposing)
        {
            if (disposing)
            {
                Flush();
            }

            base.Dispose(disposing);
        }
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
