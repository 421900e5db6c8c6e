using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Simulator.Serial;

/// <summary>
/// The host's end of an in-process link on a loaded computer (<see cref="HostLateness"/>): now and then a write is held
/// up between the moment the host stamped it and the moment its bytes leave (they leave, and the write returns, that much
/// later), and now and then the reader gets to bytes that have arrived late (they keep their arrival time; meanwhile
/// the link says bytes are waiting unread). Draws from its own seeded source, so the same seed gives the same run.
/// </summary>
internal sealed class LoadedHostLink(ISerialLink inner, TimeProvider time, HostLateness lateness, Random random) : ISerialLink
{
    private volatile bool _holding;

    public string Name => inner.Name;

    public bool HasUnreadBytes => _holding || inner.HasUnreadBytes;

    public async ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken) =>
        (await ReadStampedAsync(buffer, time, cancellationToken)).Count;

    public async ValueTask<StampedRead> ReadStampedAsync(Memory<byte> buffer, TimeProvider readTime, CancellationToken cancellationToken)
    {
        var read = await inner.ReadStampedAsync(buffer, readTime, cancellationToken);
        if (read.Count > 0 && lateness.LateReadSeconds(random) is > 0 and var late)
        {
            _holding = true;
            try
            {
                await Task.Delay(TimeSpan.FromSeconds(late), time, cancellationToken);
            }
            finally
            {
                _holding = false;
            }
        }

        return read;
    }

    public async ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken)
    {
        if (lateness.StallSeconds(random) is > 0 and var stall)
        {
            await Task.Delay(TimeSpan.FromSeconds(stall), time, cancellationToken);
        }

        await inner.WriteAsync(data, cancellationToken);
    }

    public ValueTask DisposeAsync() => inner.DisposeAsync();
}
