namespace LaserEngrave.Core.Imaging;

/// <summary>Reads Netpbm's text parts (headers and plain P1-P3 pixels): numbers between whitespace and # comments.</summary>
internal sealed class NetpbmTokenizer(ImageReader reader)
{
    private readonly byte[] _buffer = new byte[1 << 16];
    private int _start;
    private int _end;
    private long _bufferOffset = reader.Position;

    /// <summary>The file offset of the next unread byte.</summary>
    public long Position => _bufferOffset + _start;

    public long Remaining => reader.Length - Position;

    public static bool IsSpace(int b) => b is ' ' or '\t' or '\r' or '\n' or '\v' or '\f';

    public int ReadByte()
    {
        if (_start == _end && !Fill())
        {
            throw reader.Fail("the file is truncated: the Netpbm data ends early");
        }

        return _buffer[_start++];
    }

    /// <summary>A decimal number after any whitespace and comments.</summary>
    public int ReadNumber(string what)
    {
        var b = SkipSpaceAndComments();
        if (b is < '0' or > '9')
        {
            throw reader.Fail($"the Netpbm {what} is not a number (found '{(char)b}' at offset {Position - 1})");
        }

        long value = 0;
        while (b is >= '0' and <= '9')
        {
            value = (value * 10) + (b - '0');
            if (value > int.MaxValue)
            {
                throw reader.Fail($"the Netpbm {what} is too large");
            }

            if (_start == _end && !Fill())
            {
                return (int)value;
            }

            b = _buffer[_start];
            if (b is >= '0' and <= '9')
            {
                _start++;
            }
        }

        return (int)value;
    }

    /// <summary>One plain-PBM pixel: a '0' or '1', separators optional.</summary>
    public int ReadBit()
    {
        var b = SkipSpaceAndComments();
        return b switch
        {
            '0' => 0,
            '1' => 1,
            _ => throw reader.Fail($"a plain PBM pixel must be 0 or 1 (found '{(char)b}' at offset {Position - 1})"),
        };
    }

    private int SkipSpaceAndComments()
    {
        while (true)
        {
            var b = ReadByte();
            if (b == '#')
            {
                while (b is not ('\n' or '\r'))
                {
                    b = ReadByte();
                }
            }
            else if (!IsSpace(b))
            {
                return b;
            }
        }
    }

    private bool Fill()
    {
        _bufferOffset += _end;
        reader.Position = _bufferOffset;
        _start = 0;
        _end = reader.ReadAtMost(_buffer);
        return _end > 0;
    }
}
