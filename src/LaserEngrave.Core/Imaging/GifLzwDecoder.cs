namespace LaserEngrave.Core.Imaging;

/// <summary>The variable-length LZW of GIF (codes of 3 to 12 bits, clear and end codes, deferred clear).</summary>
internal static class GifLzwDecoder
{
    private const int MaxCodes = 4096;

    /// <summary>Fills <paramref name="output"/> with the indices the codes in <paramref name="data"/> stand for.</summary>
    public static void Decode(ImageReader reader, ReadOnlySpan<byte> data, int minCodeSize, Span<byte> output)
    {
        if (minCodeSize is < 1 or > 8)
        {
            throw reader.Fail($"the GIF's LZW minimum code size {minCodeSize} is not 1 to 8");
        }

        var prefix = new short[MaxCodes];
        var suffix = new byte[MaxCodes];
        var first = new byte[MaxCodes];
        var length = new short[MaxCodes];
        var clear = 1 << minCodeSize;
        var end = clear + 1;
        for (var i = 0; i < clear; i++)
        {
            suffix[i] = first[i] = (byte)i;
            length[i] = 1;
        }

        var codeSize = minCodeSize + 1;
        var next = clear + 2;
        var previous = -1;
        var written = 0;
        long bitBuffer = 0;
        var bitCount = 0;
        var pos = 0;
        while (written < output.Length)
        {
            while (bitCount < codeSize && pos < data.Length)
            {
                bitBuffer |= (long)data[pos++] << bitCount;
                bitCount += 8;
            }

            if (bitCount < codeSize)
            {
                break;
            }

            var code = (int)(bitBuffer & ((1 << codeSize) - 1));
            bitBuffer >>= codeSize;
            bitCount -= codeSize;
            if (code == clear)
            {
                codeSize = minCodeSize + 1;
                next = clear + 2;
                previous = -1;
                continue;
            }

            if (code == end)
            {
                break;
            }

            if (previous < 0)
            {
                if (code > clear)
                {
                    throw reader.Fail($"the GIF's LZW data is corrupt: code {code} before any string is defined");
                }

                output[written++] = (byte)code;
                previous = code;
                continue;
            }

            int emitted;
            if (code < next)
            {
                emitted = Emit(code, prefix, suffix, length, output[written..]);
            }
            else if (code == next && next < MaxCodes)
            {
                // The code being defined right now: the previous string plus its own first index.
                emitted = Emit(previous, prefix, suffix, length, output[written..]);
                if (written + emitted < output.Length)
                {
                    output[written + emitted] = first[previous];
                    emitted++;
                }
            }
            else
            {
                throw reader.Fail($"the GIF's LZW data is corrupt: code {code} is not yet defined (next is {next})");
            }

            if (next < MaxCodes)
            {
                prefix[next] = (short)previous;
                suffix[next] = first[code < next ? code : previous];
                first[next] = first[previous];
                length[next] = (short)(length[previous] + 1);
                next++;
                if (next == 1 << codeSize && codeSize < 12)
                {
                    codeSize++;
                }
            }

            written += emitted;
            previous = code;
        }

        if (written < output.Length)
        {
            throw reader.Fail($"the GIF image data ends after {written} of {output.Length} pixels (file truncated or corrupt)");
        }
    }

    /// <summary>Writes the string of <paramref name="code"/> (clipped to the space left) and returns how many indices it wrote.</summary>
    private static int Emit(int code, short[] prefix, byte[] suffix, short[] length, Span<byte> target)
    {
        int n = length[code];
        var count = Math.Min(n, target.Length);
        for (var i = n - 1; i >= 0; i--)
        {
            if (i < count)
            {
                target[i] = suffix[code];
            }

            code = prefix[code];
        }

        return count;
    }
}
