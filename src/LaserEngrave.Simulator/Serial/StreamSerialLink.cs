using LaserEngrave.Devices.Serial;

namespace LaserEngrave.Simulator.Serial;

/// <summary>An <see cref="ISerialLink"/> over any duplex stream, e.g. a pty opened as a file.</summary>
/// <remarks>
/// Lets the simulator sit on a pty without a serial-port library. A blocking stream (a pty file) cannot be
/// interrupted: disposing ends a pending read only once the stream itself fails or delivers, e.g. when the
/// pty pair goes away.
/// </remarks>
public sealed class StreamSerialLink(string name, Stream stream) : ISerialLink
{
    private int _disposed;

    public string Name { get; } = name;

    public async ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken)
    {
        if (Volatile.Read(ref _disposed) != 0)
        {
            return 0;
        }

        try
        {
            return await stream.ReadAsync(buffer, cancellationToken).ConfigureAwait(false);
        }
        catch (Exception ex) when (ex is ObjectDisposedException || (ex is IOException && Volatile.Read(ref _disposed) != 0))
        {
            return 0;
        }
    }

    public async ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken)
    {
        try
        {
            await stream.WriteAsync(data, cancellationToken).ConfigureAwait(false);
            await stream.FlushAsync(cancellationToken).ConfigureAwait(false);
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
            await stream.DisposeAsync().ConfigureAwait(false);
        }
    }
}
