using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Wire.Zaber;

/// <summary>Cuts received bytes into 6-byte Zaber frames under the protocol's inter-byte rule, judged on arrival times.</summary>
/// <remarks>
/// The bytes of one frame arrive less than the partial-frame timeout (10 ms) apart; an unfinished frame whose last byte
/// arrived longer ago than that when the next byte arrives is dropped. The times are when the bytes arrived, not when the
/// reader got to them: a frame in two pieces 4 ms apart that the host reads late is still one frame; where a link can only
/// bound the arrival (a real port), only a gap proven by its bounds counts (<see cref="StampedRead.EarliestArrival"/>). After garbage the
/// framer discards until the line has been quiet for the timeout. Thread-safe: the connection's resynchronisation asks
/// whether the line is quiet while the reader loop pushes bytes.
/// </remarks>
public sealed class ZaberFramer : ISerialFramer<ZaberFrame>
{
    private readonly Lock _sync = new();
    private readonly TimeSpan _partialFrameTimeout;
    private readonly TimeProvider _time;
    private readonly Action<byte[]>? _partialDropped;
    private readonly byte[] _partial = new byte[ZaberFrame.Length];
    private int _count;
    private long _lastArrival;
    private bool _anyByte;
    private bool _discarding;

    /// <param name="partialFrameTimeout">The longest gap between two bytes of one frame.</param>
    /// <param name="time">The clock of the arrival timestamps.</param>
    /// <param name="partialDropped">Told the bytes of each unfinished frame dropped after a gap (not those discarded after garbage).</param>
    public ZaberFramer(TimeSpan partialFrameTimeout, TimeProvider time, Action<byte[]>? partialDropped = null)
    {
        ArgumentNullException.ThrowIfNull(time);
        _partialFrameTimeout = partialFrameTimeout;
        _time = time;
        _partialDropped = partialDropped;
    }

    public void Push(ReadOnlySpan<byte> bytes, long arrivalTimestamp, Action<ZaberFrame> deliver) =>
        Push(bytes, new StampedRead(bytes.Length, arrivalTimestamp), deliver);

    /// <remarks>
    /// The gap is proven, not guessed: from the latest the previous bytes can have arrived (their read's stamp) to the
    /// earliest these can have (<see cref="StampedRead.EarliestArrival"/> when the link only bounds it). A piece that was
    /// already waiting when a late reader got to it has no gap proven before it, however late it was read.
    /// </remarks>
    public void Push(ReadOnlySpan<byte> bytes, StampedRead read, Action<ZaberFrame> deliver)
    {
        ArgumentNullException.ThrowIfNull(deliver);
        var arrivalTimestamp = read.ArrivalTimestamp;
        var earliest = read.EarliestArrival is { } bound ? Math.Min(bound, arrivalTimestamp) : arrivalTimestamp;
        byte[]? dropped = null;
        lock (_sync)
        {
            if (_anyByte && (_count > 0 || _discarding) && earliest > _lastArrival && _time.GetElapsedTime(_lastArrival, earliest) > _partialFrameTimeout)
            {
                if (_count > 0 && !_discarding)
                {
                    dropped = _partial[.._count];
                    LastDropGap = _time.GetElapsedTime(_lastArrival, earliest);
                }

                _count = 0;
                _discarding = false;
            }

            _anyByte = true;
            _lastArrival = arrivalTimestamp;
        }

        if (dropped is not null)
        {
            _partialDropped?.Invoke(dropped);
        }

        foreach (var b in bytes)
        {
            ZaberFrame? frame = null;
            lock (_sync)
            {
                // A frame delivered may have been garbage, which discards the rest of the burst.
                if (_discarding)
                {
                    continue;
                }

                _partial[_count++] = b;
                if (_count == ZaberFrame.Length)
                {
                    _count = 0;
                    frame = ZaberFrame.Decode(_partial);
                }
            }

            if (frame is { } complete)
            {
                deliver(complete);
            }
        }
    }

    /// <summary>The gap proven before the last unfinished frame dropped (read it in the drop's callback).</summary>
    public TimeSpan LastDropGap { get; private set; }

    /// <summary>Drops every byte until the line has been quiet for the partial-frame timeout (after garbage).</summary>
    public void DiscardUntilQuiet()
    {
        lock (_sync)
        {
            _discarding = true;
        }
    }

    /// <summary>When nothing has arrived for the partial-frame timeout, drops partial bytes and stops discarding.</summary>
    /// <returns>True when the line was quiet (frames are aligned again on this end).</returns>
    public bool ResetIfQuiet()
    {
        lock (_sync)
        {
            if (_anyByte && _time.GetElapsedTime(_lastArrival) < _partialFrameTimeout)
            {
                return false;
            }

            _count = 0;
            _discarding = false;
            return true;
        }
    }
}
