using System.Threading.Channels;

namespace LaserEngrave.Devices.Serial;

/// <summary>One end of an in-process byte pipe: what one end writes, the other reads.</summary>
public sealed class InMemorySerialLink : ISerialLink
{
    private readonly Channel<byte[]> _incoming;
    private readonly Channel<byte[]> _outgoing;
    private byte[] _pending = [];
    private int _pendingOffset;

    private InMemorySerialLink(string name, Channel<byte[]> incoming, Channel<byte[]> outgoing)
    {
        Name = name;
        _incoming = incoming;
        _outgoing = outgoing;
    }

    public string Name { get; }

    /// <summary>Makes a connected pair: (host end, device end).</summary>
    public static (InMemorySerialLink Host, InMemorySerialLink Device) CreatePair(string name = "simulator")
    {
        var toDevice = Channel.CreateUnbounded<byte[]>(new UnboundedChannelOptions { SingleReader = true });
        var toHost = Channel.CreateUnbounded<byte[]>(new UnboundedChannelOptions { SingleReader = true });
        return (new InMemorySerialLink(name, toHost, toDevice), new InMemorySerialLink(name + " (device end)", toDevice, toHost));
    }

    public async ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken)
    {
        while (_pendingOffset >= _pending.Length)
        {
            try
            {
                if (!await _incoming.Reader.WaitToReadAsync(cancellationToken))
                {
                    return 0;
                }
            }
            catch (ChannelClosedException)
            {
                return 0;
            }

            if (_incoming.Reader.TryRead(out var chunk))
            {
                _pending = chunk;
                _pendingOffset = 0;
            }
        }

        var n = Math.Min(buffer.Length, _pending.Length - _pendingOffset);
        _pending.AsMemory(_pendingOffset, n).CopyTo(buffer);
        _pendingOffset += n;
        return n;
    }

    public ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken)
    {
        if (data.IsEmpty)
        {
            return ValueTask.CompletedTask;
        }

        if (!_outgoing.Writer.TryWrite(data.ToArray()))
        {
            throw new IOException($"{Name}: the link is closed");
        }

        return ValueTask.CompletedTask;
    }

    /// <summary>Closes both directions: the other end reads end of stream, this end's pending read returns 0.</summary>
    public ValueTask DisposeAsync()
    {
        _outgoing.Writer.TryComplete();
        _incoming.Writer.TryComplete();
        return ValueTask.CompletedTask;
    }
}
