using System.Buffers.Binary;

namespace LaserEngrave.Core.Imaging;

/// <summary>
/// The few fields of a TIFF's first directory that size ImageMagick's read buffer: it holds a whole strip (or row of
/// tiles) at about 4 bytes per sample, so a header claiming one 20000-row strip costs 1.5 GB before a pixel is read.
/// </summary>
/// <param name="RowsPerBuffer">Rows per strip, or the tile length for a tiled TIFF; <see cref="uint.MaxValue"/> when the file leaves it out (one strip).</param>
/// <param name="SamplesPerPixel">Samples per pixel (1 for grey and palette, 3 for RGB ...).</param>
internal sealed record TiffDirectory(long RowsPerBuffer, int SamplesPerPixel)
{
    /// <summary>Bytes ImageMagick's TIFF reader keeps per sample of a buffered row (measured: 1.6 GB for a 20000 x 20000 single-strip page).</summary>
    public const int BufferBytesPerSample = 4;

    /// <summary>Directory entries read at most; real files have a few dozen.</summary>
    private const int MaxEntries = 4096;

    private const ushort RowsPerStripTag = 278;
    private const ushort SamplesPerPixelTag = 277;
    private const ushort TileLengthTag = 323;

    /// <summary>Bytes of ImageMagick's row buffer for an image <paramref name="width"/> x <paramref name="height"/>.</summary>
    public long BufferBytes(long width, long height) => Math.Min(RowsPerBuffer, height) * width * Math.Max(1, SamplesPerPixel) * BufferBytesPerSample;

    /// <summary>Reads the first directory; refuses a file cut before it with the offsets, where libtiff would only say it cannot read it.</summary>
    public static TiffDirectory Read(ImageReader reader)
    {
        Span<byte> head = stackalloc byte[16];
        reader.Position = 0;
        var n = reader.ReadAtMost(head);
        var bigEndian = head[0] == (byte)'M';
        var bigTiff = n >= 4 && head[bigEndian ? 3 : 2] == 43;
        var offsetAt = bigTiff ? 8 : 4;
        var offsetBytes = bigTiff ? 8 : 4;
        if (n < offsetAt + offsetBytes)
        {
            throw reader.Fail($"the file is truncated: a TIFF header needs {offsetAt + offsetBytes} bytes, but the file has {n}");
        }

        var offset = Unsigned(head.Slice(offsetAt, offsetBytes), bigEndian);

        // Writers often put the directory after the pixels, so a cut TIFF loses it first.
        if (offset >= (ulong)reader.Length)
        {
            throw reader.Fail($"the file is truncated: its first TIFF directory is at offset {offset}, but the file ends after {reader.Length} bytes");
        }

        reader.Position = (long)offset;
        Span<byte> field = stackalloc byte[20];
        var countBytes = bigTiff ? 8 : 2;
        if (reader.ReadAtMost(field[..countBytes]) < countBytes)
        {
            throw reader.Fail($"the file is truncated: the TIFF directory at offset {offset} has no entry count");
        }

        var count = Math.Min(Unsigned(field[..countBytes], bigEndian), MaxEntries);
        var entryBytes = bigTiff ? 20 : 12;
        long rows = uint.MaxValue, tileRows = 0;
        var samples = 1;
        for (ulong e = 0; e < count && reader.ReadAtMost(field[..entryBytes]) == entryBytes; e++)
        {
            var entry = field[..entryBytes];
            var tag = bigEndian ? BinaryPrimitives.ReadUInt16BigEndian(entry) : BinaryPrimitives.ReadUInt16LittleEndian(entry);
            if (tag is not (RowsPerStripTag or SamplesPerPixelTag or TileLengthTag))
            {
                continue;
            }

            var type = bigEndian ? BinaryPrimitives.ReadUInt16BigEndian(entry[2..]) : BinaryPrimitives.ReadUInt16LittleEndian(entry[2..]);
            var value = entry[(bigTiff ? 12 : 8)..];

            // SHORT values sit in the first two bytes of the value field, LONG in four, LONG8 (BigTIFF) in eight.
            var number = type switch
            {
                3 => Unsigned(value[..2], bigEndian),
                4 => Unsigned(value[..4], bigEndian),
                16 when bigTiff => Unsigned(value[..8], bigEndian),
                _ => 0UL,
            };
            switch (tag)
            {
                case RowsPerStripTag when number > 0:
                    rows = (long)Math.Min(number, uint.MaxValue);
                    break;
                case TileLengthTag when number > 0:
                    tileRows = (long)Math.Min(number, uint.MaxValue);
                    break;
                case SamplesPerPixelTag when number > 0:
                    samples = (int)Math.Min(number, 64);
                    break;
            }
        }

        return new TiffDirectory(tileRows > 0 ? tileRows : rows, samples);
    }

    private static ulong Unsigned(ReadOnlySpan<byte> bytes, bool bigEndian) => bytes.Length switch
    {
        2 => bigEndian ? BinaryPrimitives.ReadUInt16BigEndian(bytes) : BinaryPrimitives.ReadUInt16LittleEndian(bytes),
        4 => bigEndian ? BinaryPrimitives.ReadUInt32BigEndian(bytes) : BinaryPrimitives.ReadUInt32LittleEndian(bytes),
        _ => bigEndian ? BinaryPrimitives.ReadUInt64BigEndian(bytes) : BinaryPrimitives.ReadUInt64LittleEndian(bytes),
    };
}
