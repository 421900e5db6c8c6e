namespace LaserEngrave.Wire.Serial;

/// <summary>A byte link to one device: a real serial port, a pty, or an in-memory pipe to the simulator.</summary>
/// <remarks>
/// Exactly one reader loop per link calls <see cref="ReadAsync"/> or <see cref="ReadStampedAsync"/>; a read may return
/// fewer bytes than asked. Disposing the link ends a pending read with 0 (end of stream).
/// </remarks>
public interface ISerialLink : IAsyncDisposable
{
    /// <summary>Port name or path, for messages.</summary>
    string Name { get; }

    /// <summary>Reads at least one byte, or returns 0 when the link is closed.</summary>
    ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken);

    /// <summary>Reads at least one byte of what arrived together, with the time it arrived (not the time it was read).</summary>
    /// <param name="buffer">Where the bytes go.</param>
    /// <param name="time">The clock the arrival is given on (the reader's: the wall clock, or the simulation's).</param>
    /// <param name="cancellationToken">Cancels the read.</param>
    /// <returns>The bytes read (0: the link is closed) and their arrival as a timestamp of <paramref name="time"/>.</returns>
    ValueTask<StampedRead> ReadStampedAsync(Memory<byte> buffer, TimeProvider time, CancellationToken cancellationToken);

    /// <summary>True when bytes have arrived that no read has returned yet (false when the link cannot tell).</summary>
    /// <remarks>Asked from any thread, when a reply's time is up: bytes already here may be that reply, noticed late.</remarks>
    bool HasUnreadBytes { get; }

    /// <summary>Writes all of <paramref name="data"/>.</summary>
    ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken);
}
