using System.Buffers;
using System.Text;
using System.Text.Unicode;

namespace LaserEngrave.Core.IO;

/// <summary>
/// Reads the text files a person writes (job files, profiles, marks, run logs) as UTF-8, or UTF-16 when the file starts
/// with its byte order mark; anything else is refused naming the line, never turned silently into replacement
/// characters (a Windows-1252 "Größe" would otherwise read as "Gr��e" and be burned or logged so).
/// </summary>
public static class TextFile
{
    /// <summary>The file's text; throws <see cref="TextEncodingException"/> naming the line when it is not UTF-8 (or UTF-16 with a BOM), an <see cref="IOException"/> when it cannot be read.</summary>
    public static string Read(string path)
    {
        ArgumentException.ThrowIfNullOrEmpty(path);
        return Decode(File.ReadAllBytes(path));
    }

    /// <summary>The text of <paramref name="bytes"/>; throws <see cref="TextEncodingException"/> when they are not UTF-8 (or UTF-16 with a BOM).</summary>
    public static string Decode(byte[] bytes)
    {
        ArgumentNullException.ThrowIfNull(bytes);
        if (bytes is [0xFF, 0xFE, ..] or [0xFE, 0xFF, ..])
        {
            var encoding = new UnicodeEncoding(bigEndian: bytes[0] == 0xFE, byteOrderMark: false, throwOnInvalidBytes: true);
            try
            {
                return encoding.GetString(bytes, 2, bytes.Length - 2);
            }
            catch (DecoderFallbackException)
            {
                // UTF-16's only invalid sequences are lone surrogates and an odd last byte: rare enough to name the file, not the line.
                throw new TextEncodingException("is not valid UTF-16 text although it starts with UTF-16's byte order mark: save it again as UTF-8");
            }
        }

        var start = bytes is [0xEF, 0xBB, 0xBF, ..] ? 3 : 0;
        var source = bytes.AsSpan(start);
        var chars = ArrayPool<char>.Shared.Rent(Math.Max(1, source.Length));
        try
        {
            var status = Utf8.ToUtf16(source, chars, out var read, out var written, replaceInvalidSequences: false);
            if (status == OperationStatus.Done)
            {
                return new string(chars, 0, written);
            }

            throw new TextEncodingException(Where(source, read));
        }
        finally
        {
            ArrayPool<char>.Shared.Return(chars);
        }
    }

    /// <summary>"line 3, column 7 is not UTF-8 text (byte 0xF6): ..." for the first byte that is not UTF-8 at <paramref name="index"/>.</summary>
    private static string Where(ReadOnlySpan<byte> source, int index)
    {
        var before = source[..index];
        var line = before.Count((byte)'\n') + 1;
        var lineStart = before.LastIndexOf((byte)'\n') + 1;

        // Columns in characters, as an editor counts them: the line's valid UTF-8 up to the bad byte.
        var column = Encoding.UTF8.GetCharCount(before[lineStart..]) + 1;
        var bad = index < source.Length ? source[index] : (byte)0;
        var guess = bad is >= 0x80 and <= 0xFF ? " (it looks like Windows-1252 or Latin-1, e.g. ö or ß saved by an older editor)" : string.Empty;
        return $"line {line}, column {column} is not UTF-8 text (byte 0x{bad:X2}){guess}: save the file as UTF-8";
    }
}

/// <summary>A text file that is not UTF-8 (or UTF-16 with a BOM); the message names the line, without the path.</summary>
public sealed class TextEncodingException(string message) : IOException(message);
