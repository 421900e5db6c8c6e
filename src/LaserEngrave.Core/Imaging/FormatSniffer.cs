namespace LaserEngrave.Core.Imaging;

/// <summary>Tells the format of a file from its first bytes, and refuses the formats this build cannot decode.</summary>
internal static class FormatSniffer
{
    /// <summary>Bytes enough for every signature checked here.</summary>
    public const int SignatureLength = 16;

    /// <summary>The decodable format of <paramref name="reader"/>'s file; leaves the position at 0.</summary>
    public static ImageFormat Detect(ImageReader reader)
    {
        if (reader.Length == 0)
        {
            throw reader.Fail("the file is empty");
        }

        Span<byte> head = stackalloc byte[SignatureLength];
        reader.Position = 0;
        var n = reader.ReadAtMost(head);
        reader.Position = 0;
        var format = Detect(head[..n], out var unsupported);
        if (format is { } known)
        {
            return known;
        }

        if (unsupported is not null)
        {
            throw reader.Fail($"{unsupported} image: no decoder for that format is available in this build; save it as PNG or BMP and load that");
        }

        // Never the file's bytes: the message reaches the API's answer, and the file may be any file on this computer.
        throw reader.Fail("not a BMP, PNG, GIF, JPEG, TIFF, WebP or Netpbm image");
    }

    /// <summary>The format, or null with <paramref name="unsupported"/> naming a recognised format that has no decoder.</summary>
    public static ImageFormat? Detect(ReadOnlySpan<byte> head, out string? unsupported)
    {
        unsupported = null;
        if (head.StartsWith("BM"u8))
        {
            return ImageFormat.Bmp;
        }

        if (head.StartsWith((ReadOnlySpan<byte>)[0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A]))
        {
            return ImageFormat.Png;
        }

        if (head.StartsWith("GIF87a"u8) || head.StartsWith("GIF89a"u8))
        {
            return ImageFormat.Gif;
        }

        if (head.StartsWith((ReadOnlySpan<byte>)[0xFF, 0xD8, 0xFF]))
        {
            return ImageFormat.Jpeg;
        }

        if (head.StartsWith("II*\0"u8) || head.StartsWith("MM\0*"u8) || head.StartsWith("II+\0"u8) || head.StartsWith("MM\0+"u8))
        {
            return ImageFormat.Tiff;
        }

        if (head.Length >= 12 && head.StartsWith("RIFF"u8) && head.Slice(8, 4).SequenceEqual("WEBP"u8))
        {
            return ImageFormat.WebP;
        }

        if (head.Length >= 3 && head[0] == (byte)'P' && IsNetpbmSpace(head[2]))
        {
            switch (head[1])
            {
                case (byte)'1' or (byte)'4':
                    return ImageFormat.Pbm;
                case (byte)'2' or (byte)'5':
                    return ImageFormat.Pgm;
                case (byte)'3' or (byte)'6':
                    return ImageFormat.Ppm;
                case (byte)'7':
                    unsupported = "PAM (Netpbm P7)";
                    return null;
                case (byte)'F' or (byte)'f':
                    unsupported = "PFM (floating-point Netpbm)";
                    return null;
            }
        }

        unsupported = DetectUnsupported(head);
        return null;
    }

    private static string? DetectUnsupported(ReadOnlySpan<byte> head)
    {
        if (head.StartsWith("BA"u8) || head.StartsWith("CI"u8) || head.StartsWith("CP"u8) || head.StartsWith("IC"u8) || head.StartsWith("PT"u8))
        {
            return "OS/2 bitmap array, icon or pointer";
        }

        if (head.Length >= 12 && head.Slice(4, 4).SequenceEqual("ftyp"u8))
        {
            return "HEIF/AVIF";
        }

        if (head.StartsWith("qoif"u8))
        {
            return "QOI";
        }

        if (head.StartsWith("8BPS"u8))
        {
            return "Photoshop";
        }

        if (head.StartsWith("%PDF"u8))
        {
            return "PDF";
        }

        return null;
    }

    private static bool IsNetpbmSpace(byte b) => b is (byte)' ' or (byte)'\t' or (byte)'\r' or (byte)'\n' or (byte)'\v' or (byte)'\f' or (byte)'#';
}
