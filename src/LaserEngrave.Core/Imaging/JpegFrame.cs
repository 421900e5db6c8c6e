using System.Buffers.Binary;

namespace LaserEngrave.Core.Imaging;

/// <summary>
/// A JPEG's frame header (SOF marker, width, height), read to check that the file can hold the picture it claims
/// before ImageMagick allocates for it.
/// </summary>
/// <remarks>
/// Huffman-coded JPEG spends at least one bit on every 8 x 8 block of its full-resolution component (the DC code of the
/// first scan), so a real file of W x H pixels holds at least W x H / 512 bytes; a 300-byte file claiming 16000 x 16000
/// made ImageMagick fill 1 GB with grey before failing. Arithmetic-coded JPEG has no such floor.
/// </remarks>
/// <param name="Marker">The SOF marker's second byte (0xC0 baseline, 0xC2 progressive, 0xC9 arithmetic ...).</param>
internal sealed record JpegFrame(int Marker, int Width, int Height)
{
    /// <summary>Whether the scans are Huffman-coded DCT (baseline, extended, progressive), which bounds the data a picture needs.</summary>
    public bool IsHuffmanDct => Marker is 0xC0 or 0xC1 or 0xC2;

    /// <summary>The fewest bytes of scan data the picture can take: one bit per 8 x 8 block.</summary>
    public long MinimumScanBytes => ((Width + 7L) / 8) * ((Height + 7L) / 8) / 8;

    /// <summary>The first frame header, or null when the markers end (or a scan starts) before one.</summary>
    public static JpegFrame? Read(ImageReader reader)
    {
        Span<byte> segment = stackalloc byte[7];
        reader.Position = 2;
        while (reader.ReadAtMost(segment[..2]) == 2)
        {
            if (segment[0] != 0xFF)
            {
                return null;
            }

            var marker = segment[1];
            if (marker == 0xFF)
            {
                // Fill bytes may pad before a marker.
                reader.Position--;
                continue;
            }

            if (marker is 0x01 or (>= 0xD0 and <= 0xD7))
            {
                continue;
            }

            if (marker == 0xDA || reader.ReadAtMost(segment[..2]) < 2)
            {
                return null;
            }

            var length = BinaryPrimitives.ReadUInt16BigEndian(segment);
            if (marker is >= 0xC0 and <= 0xCF and not (0xC4 or 0xC8 or 0xCC))
            {
                return reader.ReadAtMost(segment[..5]) < 5
                    ? null
                    : new JpegFrame(marker, BinaryPrimitives.ReadUInt16BigEndian(segment[3..]), BinaryPrimitives.ReadUInt16BigEndian(segment[1..]));
            }

            if (length < 2 || reader.Position + length - 2 > reader.Length)
            {
                return null;
            }

            reader.Position += length - 2;
        }

        return null;
    }
}
