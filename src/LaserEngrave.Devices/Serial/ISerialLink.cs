namespace LaserEngrave.Devices.Serial;

/// <summary>A byte link to one device: a real serial port, a pty, or an in-memory pipe to the simulator.</summary>
/// <remarks>
/// Exactly one reader loop per link calls <see cref="ReadAsync"/>; a read may return fewer bytes than asked.
/// Disposing the link ends a pending read with 0 (end of stream).
/// </remarks>
public interface ISerialLink : IAsyncDisposable
{
    /// <summary>Port name or path, for messages.</summary>
    string Name { get; }

    /// <summary>Reads at least one byte, or returns 0 when the link is closed.</summary>
    ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken);

    /// <summary>Writes all of <paramref name="data"/>.</summary>
    ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken);
}
