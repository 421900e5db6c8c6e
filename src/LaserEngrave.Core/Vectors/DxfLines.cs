namespace LaserEngrave.Core.Vectors;

/// <summary>
/// The lines of a DXF file, read as they come instead of all at once: cut at each line feed only (a carriage return
/// stays in the line, as <c>string.Split('\n')</c> leaves it), blank lines at the end of the file dropped.
/// </summary>
/// <remarks>
/// A 16 MB file of 300 000 LINEs was read whole, then split into 3.4 million line strings, then into groups: 570 MiB
/// allocated before a single entity was kept (issue 38). Here a line is a span of one reusable buffer, so only the
/// values the entities keep become strings. A blank line is handed out as an empty span.
/// </remarks>
internal sealed class DxfLines(TextReader reader)
{
    private char[] _buffer = new char[1 << 16];
    private int _start;
    private int _end;
    private bool _endOfText;
    private int _lineStart;
    private int _lineLength;

    // Blank lines read ahead to see whether anything followed them, and the line that did (a copy: the buffer moves on).
    private int _blanksAhead;
    private string? _held;
    private string? _heldCurrent;
    private bool _onHeld;
    private int _number;

    /// <summary>The current line (empty when it is blank); valid until the next <see cref="MoveNext"/>.</summary>
    public ReadOnlySpan<char> Current => _onHeld ? _heldCurrent : _buffer.AsSpan(_lineStart, _lineLength);

    /// <summary>The current line's number, from 1.</summary>
    public int Number => _number;

    /// <summary>Moves to the next line; false past the last line that is not blank.</summary>
    public bool MoveNext()
    {
        _onHeld = false;
        if (_blanksAhead > 0)
        {
            _blanksAhead--;
            _number++;
            _lineLength = 0;
            return true;
        }

        if (_held is not null)
        {
            _heldCurrent = _held;
            _held = null;
            _onHeld = true;
            _number++;
            return true;
        }

        if (!ReadLine())
        {
            return false;
        }

        _number++;
        if (!IsBlank())
        {
            return true;
        }

        // A blank line counts only when a line that is not blank comes after it.
        var blanks = 0;
        while (ReadLine())
        {
            if (!IsBlank())
            {
                _held = new string(_buffer, _lineStart, _lineLength);
                _blanksAhead = blanks;
                _lineLength = 0;
                return true;
            }

            blanks++;
        }

        return false;
    }

    private bool IsBlank() => _buffer.AsSpan(_lineStart, _lineLength).Trim().IsEmpty;

    // The next raw line into _lineStart/_lineLength; false at the end of the text.
    private bool ReadLine()
    {
        var scanned = _start;
        while (true)
        {
            var feed = _buffer.AsSpan(scanned, _end - scanned).IndexOf('\n');
            if (feed >= 0)
            {
                _lineStart = _start;
                _lineLength = scanned + feed - _start;
                _start = scanned + feed + 1;
                return true;
            }

            if (_endOfText)
            {
                // The text after the last line feed is the last line (when empty, a blank one, which would be dropped anyway).
                if (_start == _end)
                {
                    return false;
                }

                _lineStart = _start;
                _lineLength = _end - _start;
                _start = _end;
                return true;
            }

            scanned = _end - _start;
            Fill();
        }
    }

    private void Fill()
    {
        if (_start > 0)
        {
            Array.Copy(_buffer, _start, _buffer, 0, _end - _start);
            _end -= _start;
            _start = 0;
        }

        if (_end == _buffer.Length)
        {
            // A line longer than the buffer.
            Array.Resize(ref _buffer, _buffer.Length * 2);
        }

        var read = reader.Read(_buffer, _end, _buffer.Length - _end);
        if (read == 0)
        {
            _endOfText = true;
        }
        else
        {
            _end += read;
        }
    }
}
