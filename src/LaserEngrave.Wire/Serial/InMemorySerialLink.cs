using System.Threading.Channels;

namespace LaserEngrave.Wire.Serial;

/// <summary>One end of an in-process byte pipe: what one end writes, the other reads.</summary>
/// <remarks>
/// With a clock, every write is stamped with the time it was made (the simulator writes each reply when it is delivered),
/// and a read hands that stamp on as the bytes' arrival, however late the reader gets to them; without one, bytes arrive
/// when they are read.
/// </remarks>
public sealed class InMemorySerialLink : ISerialLink
{
    private readonly Channel<Chunk> _incoming;
    private readonly Channel<Chunk> _outgoing;
    private readonly TimeProvider? _clock;
    private Chunk _pending = new([], null);
    private int _pendingOffset;

    private InMemorySerialLink(string name, Channel<Chunk> incoming, Channel<Chunk> outgoing, TimeProvider? clock)
    {
        Name = name;
        _incoming = incoming;
        _outgoing = outgoing;
        _clock = clock;
    }

    public string Name { get; }

    public bool HasUnreadBytes => Volatile.Read(ref _pendingOffset) < _pending.Data.Length || _incoming.Reader.TryPeek(out _);

    /// <summary>Makes a connected pair: (host end, device end).</summary>
    /// <param name="name">The host end's name; the device end's adds "(device end)".</param>
    /// <param name="clock">Stamps every write with its time; null: bytes arrive when they are read.</param>
    public static (InMemorySerialLink Host, InMemorySerialLink Device) CreatePair(string name = "simulator", TimeProvider? clock = null)
    {
        var toDevice = Channel.CreateUnbounded<Chunk>(new UnboundedChannelOptions { SingleReader = true });
        var toHost = Channel.CreateUnbounded<Chunk>(new UnboundedChannelOptions { SingleReader = true });
        return (new InMemorySerialLink(name, toHost, toDevice, clock), new InMemorySerialLink(name + " (device end)", toDevice, toHost, clock));
    }

    public async ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken) =>
        (await ReadChunkAsync(buffer, cancellationToken)).Count;

    public async ValueTask<StampedRead> ReadStampedAsync(Memory<byte> buffer, TimeProvider time, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(time);
        var (count, stamp) = await ReadChunkAsync(buffer, cancellationToken);
        return new StampedRead(count, stamp is { } arrival && _clock is not null ? StampedRead.OnClock(arrival, _clock, time) : time.GetTimestamp());
    }

    public ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken) => Write(data, _clock?.GetTimestamp());

    /// <summary>Writes bytes that the other end reads as having arrived at <paramref name="arrivalTimestamp"/> (on this pair's clock).</summary>
    /// <remarks>For a writer that models the delivery itself, or a test of a host that gets to its bytes late.</remarks>
    public ValueTask WriteArrivedAsync(ReadOnlyMemory<byte> data, long arrivalTimestamp)
    {
        if (_clock is null)
        {
            throw new InvalidOperationException($"{Name}: a pair made without a clock has no arrival times");
        }

        return Write(data, arrivalTimestamp);
    }

    /// <summary>Closes both directions: the other end reads end of stream, this end's pending read returns 0.</summary>
    public ValueTask DisposeAsync()
    {
        _outgoing.Writer.TryComplete();
        _incoming.Writer.TryComplete();
        return ValueTask.CompletedTask;
    }

    private ValueTask Write(ReadOnlyMemory<byte> data, long? stamp)
    {
        if (data.IsEmpty)
        {
            return ValueTask.CompletedTask;
        }

        if (!_outgoing.Writer.TryWrite(new Chunk(data.ToArray(), stamp)))
        {
            throw new IOException($"{Name}: the link is closed");
        }

        return ValueTask.CompletedTask;
    }

    // One read never mixes two writes, so each keeps its own arrival.
    private async ValueTask<(int Count, long? Stamp)> ReadChunkAsync(Memory<byte> buffer, CancellationToken cancellationToken)
    {
        while (_pendingOffset >= _pending.Data.Length)
        {
            try
            {
                if (!await _incoming.Reader.WaitToReadAsync(cancellationToken))
                {
                    return (0, null);
                }
            }
            catch (ChannelClosedException)
            {
                return (0, null);
            }

            if (_incoming.Reader.TryRead(out var chunk))
            {
                _pending = chunk;
                _pendingOffset = 0;
            }
        }

        var n = Math.Min(buffer.Length, _pending.Data.Length - _pendingOffset);
        _pending.Data.AsMemory(_pendingOffset, n).CopyTo(buffer);
        _pendingOffset += n;
        return (n, _pending.Stamp);
    }

    private sealed record Chunk(byte[] Data, long? Stamp);
}
