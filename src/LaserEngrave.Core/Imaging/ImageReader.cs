namespace LaserEngrave.Core.Imaging;

/// <summary>A seekable image source that knows its length and its name, and turns running out of bytes into a clear error.</summary>
internal sealed class ImageReader : IDisposable
{
    private readonly Stream _stream;
    private readonly bool _ownsStream;

    public ImageReader(Stream stream, string path, bool ownsStream)
    {
        ArgumentNullException.ThrowIfNull(stream);
        if (!stream.CanSeek || !stream.CanRead)
        {
            throw new ArgumentException("the stream must be readable and seekable", nameof(stream));
        }

        _stream = stream;
        _ownsStream = ownsStream;
        Path = path;
        Length = stream.Length;
    }

    public string Path { get; }

    public long Length { get; }

    public long Position
    {
        get => _stream.Position;
        set => _stream.Position = value;
    }

    public long Remaining => Length - _stream.Position;

    /// <summary>The underlying seekable stream, for a library decoder that reads it itself (ImageMagick).</summary>
    public Stream BaseStream => _stream;

    public static ImageReader Open(string path)
    {
        // Opening a FIFO would block until something writes to it; a folder or a device is never an image.
        if (IO.RegularFile.Problem(path) is { } problem)
        {
            throw new ImageLoadException(path, problem);
        }

        var stream = new FileStream(path, FileMode.Open, FileAccess.Read, FileShare.Read, bufferSize: 1 << 16, FileOptions.SequentialScan);
        return new ImageReader(stream, path, ownsStream: true);
    }

    public ImageLoadException Fail(string problem) => new(Path, problem);

    /// <summary>Fills <paramref name="buffer"/> or fails saying the file is truncated in <paramref name="what"/>.</summary>
    public void ReadExactly(Span<byte> buffer, string what)
    {
        var start = _stream.Position;
        var read = _stream.ReadAtLeast(buffer, buffer.Length, throwOnEndOfStream: false);
        if (read < buffer.Length)
        {
            throw Fail($"the file is truncated: {what} needs {buffer.Length} bytes at offset {start}, but the file ends after {read}");
        }
    }

    /// <summary>Reads up to <paramref name="buffer"/>.Length bytes, fewer only at the end of the file.</summary>
    public int ReadAtMost(Span<byte> buffer) => _stream.ReadAtLeast(buffer, buffer.Length, throwOnEndOfStream: false);

    public byte ReadByte(string what)
    {
        var b = _stream.ReadByte();
        return b < 0 ? throw Fail($"the file is truncated: it ends in {what} at offset {_stream.Position}") : (byte)b;
    }

    /// <summary>Reads a block whose size came from the file, after checking the file really holds it.</summary>
    public byte[] ReadBlock(long count, string what)
    {
        if (count < 0 || count > Remaining)
        {
            throw Fail($"the file is truncated: {what} needs {count} bytes at offset {Position}, but only {Remaining} remain");
        }

        var block = new byte[count];
        ReadExactly(block, what);
        return block;
    }

    public void Skip(long count, string what)
    {
        if (count < 0 || count > Remaining)
        {
            throw Fail($"the file is truncated: {what} needs {count} bytes at offset {Position}, but only {Remaining} remain");
        }

        _stream.Position += count;
    }

    public void Dispose()
    {
        if (_ownsStream)
        {
            _stream.Dispose();
        }
    }
}
