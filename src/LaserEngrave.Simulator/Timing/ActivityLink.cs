using LaserEngrave.Devices.Serial;

namespace LaserEngrave.Simulator.Timing;

/// <summary>The host's end of an in-process link: it tells the clock about every byte, and holds it while the host handles what it read.</summary>
/// <remarks>
/// The hold lasts from a read returning until the host's reader loop comes back for more, so a reply is dispatched to
/// its waiter (which then no longer times out) before virtual time may move on.
/// </remarks>
internal sealed class ActivityLink(ISerialLink inner, SimulationClock clock) : ISerialLink
{
    private ClockHold _handling;

    public string Name => inner.Name;

    public async ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken)
    {
        _handling.Dispose();
        _handling = default;
        var n = await inner.ReadAsync(buffer, cancellationToken).ConfigureAwait(false);
        clock.Signal();
        if (n > 0)
        {
            _handling = clock.Hold();
        }

        return n;
    }

    public ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken)
    {
        clock.Signal();
        return inner.WriteAsync(data, cancellationToken);
    }

    public ValueTask DisposeAsync()
    {
        _handling.Dispose();
        return inner.DisposeAsync();
    }
}
