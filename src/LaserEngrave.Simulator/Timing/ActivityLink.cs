using System.Collections.Concurrent;
using LaserEngrave.Devices.Serial;

namespace LaserEngrave.Simulator.Timing;

/// <summary>One end of an in-process link that keeps a virtual clock still while bytes are in flight or being handled.</summary>
/// <remarks>
/// Every write holds the clock until the other end has read the bytes. On the host's end every read also holds it until
/// the host's reader loop comes back for more, so a reply reaches its waiter (whose timeout then no longer matters)
/// before virtual time may move on, however slowly the threads involved are scheduled. That hold lapses after
/// <see cref="HandlingLimit"/>, in case the reader waits on a timer between reads; the simulator's end needs none,
/// its session holds the clock itself. Unread bytes hold it for at most <see cref="VirtualTimeProvider.BlockedCallbackLimit"/>.
/// </remarks>
internal sealed class ActivityLink : ISerialLink
{
    private readonly ISerialLink _inner;
    private readonly SimulationClock _clock;
    private readonly ConcurrentQueue<ClockHold> _sent;
    private readonly ConcurrentQueue<ClockHold> _received;
    private readonly bool _holdWhileHandling;
    private ClockHold _handling;

    private ActivityLink(ISerialLink inner, SimulationClock clock, ConcurrentQueue<ClockHold> sent, ConcurrentQueue<ClockHold> received, bool holdWhileHandling)
    {
        _inner = inner;
        _clock = clock;
        _sent = sent;
        _received = received;
        _holdWhileHandling = holdWhileHandling;
    }

    /// <summary>Longest the host's handling of one read holds the clock (wall clock).</summary>
    public static TimeSpan HandlingLimit { get; } = TimeSpan.FromMilliseconds(50);

    public string Name => _inner.Name;

    /// <summary>Wraps both ends of an in-memory pair.</summary>
    public static (ActivityLink Host, ActivityLink Device) WrapPair(ISerialLink host, ISerialLink device, SimulationClock clock)
    {
        var toDevice = new ConcurrentQueue<ClockHold>();
        var toHost = new ConcurrentQueue<ClockHold>();
        return (new ActivityLink(host, clock, toDevice, toHost, holdWhileHandling: true), new ActivityLink(device, clock, toHost, toDevice, holdWhileHandling: false));
    }

    public async ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken)
    {
        _handling.Dispose();
        _handling = default;
        var n = await _inner.ReadAsync(buffer, cancellationToken).ConfigureAwait(false);
        if (n > 0 && _holdWhileHandling)
        {
            _handling = _clock.Hold(HandlingLimit);
        }

        Release(_received);
        _clock.Signal();
        return n;
    }

    public async ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken)
    {
        _clock.Signal();
        _sent.Enqueue(_clock.Hold());
        try
        {
            await _inner.WriteAsync(data, cancellationToken).ConfigureAwait(false);
        }
        catch
        {
            Release(_sent);
            throw;
        }
    }

    public ValueTask DisposeAsync()
    {
        _handling.Dispose();
        Release(_sent);
        Release(_received);
        return _inner.DisposeAsync();
    }

    private static void Release(ConcurrentQueue<ClockHold> holds)
    {
        while (holds.TryDequeue(out var hold))
        {
            hold.Dispose();
        }
    }
}
