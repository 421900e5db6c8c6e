namespace LaserEngrave.Devices.Serial;

/// <summary>The operating system's side of one open serial port, driven by <see cref="NativeSerialPort"/>.</summary>
/// <remarks>Blocking calls on purpose: one dedicated thread reads, writers hold a lock, <see cref="Interrupt"/> frees both.</remarks>
internal abstract class SerialPortBackend : IDisposable
{
    /// <summary>Blocks until at least one byte is read (returns how many) or <see cref="Interrupt"/> is called (returns 0).</summary>
    /// <exception cref="IOException">The port failed: unplugged, hung up, closed by the driver.</exception>
    public abstract int Read(Span<byte> buffer);

    /// <summary>Writes every byte, blocking while the driver's buffer is full.</summary>
    /// <exception cref="IOException">The port failed or was interrupted.</exception>
    public abstract void Write(ReadOnlySpan<byte> data);

    /// <summary>Makes a blocked <see cref="Read"/> or <see cref="Write"/> return promptly; safe from any thread, idempotent.</summary>
    public abstract void Interrupt();

    /// <summary>Closes the port; called only once no thread is inside <see cref="Read"/> or <see cref="Write"/>.</summary>
    public abstract void Dispose();
}
