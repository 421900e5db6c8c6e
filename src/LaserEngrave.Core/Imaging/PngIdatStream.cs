using System.Buffers.Binary;

namespace LaserEngrave.Core.Imaging;

/// <summary>The payload of consecutive IDAT chunks as one stream, checking each chunk's CRC as it is read.</summary>
internal sealed class PngIdatStream : Stream
{
    private readonly ImageReader _reader;
    private long _remainingInChunk;
    private uint _crc;
    private bool _done;

    /// <summary>Starts at the length field of the first IDAT chunk.</summary>
    public PngIdatStream(ImageReader reader, long firstIdatOffset)
    {
        _reader = reader;
        _reader.Position = firstIdatOffset;
        NextChunk();
    }

    public override bool CanRead => true;

    public override bool CanSeek => false;

    public override bool CanWrite => false;

    public override long Length => throw new NotSupportedException();

    public override long Position
    {
        get => throw new NotSupportedException();
        set => throw new NotSupportedException();
    }

    public override int Read(byte[] buffer, int offset, int count) => Read(buffer.AsSpan(offset, count));

    public override int Read(Span<byte> buffer)
    {
        while (_remainingInChunk == 0 && !_done)
        {
            FinishChunk();
            NextChunk();
        }

        if (_done || buffer.IsEmpty)
        {
            return 0;
        }

        var n = _reader.ReadAtMost(buffer[..(int)Math.Min(buffer.Length, _remainingInChunk)]);
        if (n == 0)
        {
            throw _reader.Fail("the file is truncated inside the PNG image data");
        }

        _crc = Crc32.Update(_crc, buffer[..n]);
        _remainingInChunk -= n;
        return n;
    }

    /// <summary>Reads what is left of the image data, so every IDAT chunk's CRC gets checked, including the last one.</summary>
    public void CheckRemainingChunks()
    {
        Span<byte> scratch = stackalloc byte[4096];
        while (Read(scratch) > 0)
        {
        }
    }

    public override void Flush()
    {
    }

    public override long Seek(long offset, SeekOrigin origin) => throw new NotSupportedException();

    public override void SetLength(long value) => throw new NotSupportedException();

    public override void Write(byte[] buffer, int offset, int count) => throw new NotSupportedException();

    private void NextChunk()
    {
        Span<byte> header = stackalloc byte[8];
        if (_reader.Remaining < header.Length)
        {
            _done = true;
            return;
        }

        _reader.ReadExactly(header, "a PNG chunk header");
        if (!header[4..].SequenceEqual("IDAT"u8))
        {
            _done = true;
            return;
        }

        _remainingInChunk = BinaryPrimitives.ReadUInt32BigEndian(header);
        if (_remainingInChunk + 4 > _reader.Remaining)
        {
            throw _reader.Fail($"the file is truncated: an IDAT chunk claims {_remainingInChunk} bytes, but only {_reader.Remaining} remain");
        }

        _crc = Crc32.Update(Crc32.Start, "IDAT"u8);
    }

    private void FinishChunk()
    {
        Span<byte> stored = stackalloc byte[4];
        _reader.ReadExactly(stored, "the CRC of an IDAT chunk");
        if (Crc32.Finish(_crc) != BinaryPrimitives.ReadUInt32BigEndian(stored))
        {
            throw _reader.Fail($"a PNG IDAT chunk ending at offset {_reader.Position} fails its CRC check (the file is corrupt)");
        }
    }
}
