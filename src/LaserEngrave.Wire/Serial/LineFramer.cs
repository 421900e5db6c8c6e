using System.Text;

namespace LaserEngrave.Wire.Serial;

/// <summary>ASCII lines ended by '\n', '\r' or both; empty lines are skipped and a line is cut at a maximum length.</summary>
public sealed class LineFramer : ISerialFramer<string>
{
    private readonly StringBuilder _line = new();
    private readonly int _maxLength;

    /// <param name="maxLength">Characters kept of one line; the rest of a longer one is dropped.</param>
    public LineFramer(int maxLength = 1024)
    {
        ArgumentOutOfRangeException.ThrowIfNegativeOrZero(maxLength);
        _maxLength = maxLength;
    }

    public void Push(ReadOnlySpan<byte> bytes, long arrivalTimestamp, Action<string> deliver)
    {
        ArgumentNullException.ThrowIfNull(deliver);
        foreach (var b in bytes)
        {
            var c = (char)b;
            if (c is '\n' or '\r')
            {
                if (_line.Length > 0)
                {
                    var line = _line.ToString();
                    _line.Clear();
                    deliver(line);
                }
            }
            else if (_line.Length < _maxLength)
            {
                _line.Append(c);
            }
        }
    }
}
