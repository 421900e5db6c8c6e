using System.Threading.Channels;
using LaserEngrave.Devices.Serial;

namespace LaserEngrave.Simulator.Serial;

/// <summary>An <see cref="ISerialLink"/> over any duplex stream, e.g. a pty opened as a file.</summary>
/// <remarks>
/// Lets the simulator sit on a pty without a serial-port library. Reads of a pty file block and ignore cancellation,
/// so one dedicated thread reads the stream into a queue: reads through the link are cancellable, a closed link reads
/// end of stream at once, and blocked reads never starve the thread pool. The thread itself ends when the stream fails
/// or ends (e.g. when the pty pair goes away).
/// </remarks>
public sealed class StreamSerialLink : ISerialLink
{
    private readonly Stream _stream;
    private readonly Channel<byte[]> _received = Channel.CreateUnbounded<byte[]>(new UnboundedChannelOptions { SingleReader = true, SingleWriter = true });
    private byte[] _pending = [];
    private int _pendingOffset;
    private int _disposed;
    private Exception? _failure;

    public StreamSerialLink(string name, Stream stream)
    {
        ArgumentNullException.ThrowIfNull(stream);
        Name = name;
        _stream = stream;
        new Thread(Pump) { IsBackground = true, Name = $"read {name}" }.Start();
    }

    public string Name { get; }

    public async ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken)
    {
        while (_pendingOffset >= _pending.Length)
        {
            if (!await _received.Reader.WaitToReadAsync(cancellationToken).ConfigureAwait(false) || !_received.Reader.TryRead(out var chunk))
            {
                return _failure is { } failure && Volatile.Read(ref _disposed) == 0
                    ? throw new IOException($"{Name}: {failure.Message}", failure)
                    : 0;
            }

            (_pending, _pendingOffset) = (chunk, 0);
        }

        var n = Math.Min(buffer.Length, _pending.Length - _pendingOffset);
        _pending.AsMemory(_pendingOffset, n).CopyTo(buffer);
        _pendingOffset += n;
        return n;
    }

    public async ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken)
    {
        if (Volatile.Read(ref _disposed) != 0)
        {
            throw new IOException($"{Name}: the link is closed");
        }

        try
        {
            await _stream.WriteAsync(data, cancellationToken).ConfigureAwait(false);
            await _stream.FlushAsync(cancellationToken).ConfigureAwait(false);
        }
        catch (ObjectDisposedException ex)
        {
            throw new IOException($"{Name}: the link is closed", ex);
        }
    }

    public async ValueTask DisposeAsync()
    {
        if (Interlocked.Exchange(ref _disposed, 1) == 0)
        {
            _received.Writer.TryComplete();
            await _stream.DisposeAsync().ConfigureAwait(false);
        }
    }

    private void Pump()
    {
        var buffer = new byte[4096];
        try
        {
            int n;
            while ((n = _stream.Read(buffer)) > 0)
            {
                _received.Writer.TryWrite(buffer[..n]);
            }

            _received.Writer.TryComplete();
        }
        catch (Exception ex) when (ex is IOException or ObjectDisposedException)
        {
            _failure = ex;
            _received.Writer.TryComplete();
        }
    }
}
