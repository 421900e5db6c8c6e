using LaserEngrave.Wire.Serial;


namespace LaserEngrave.Devices.Tests.Fakes;

/// <summary>A host end whose reader is held back: bytes arrive (and are reported unread) but no read returns until released.</summary>
/// <remarks>Stands for a host too busy to read what has already arrived, as on a loaded machine.</remarks>
public sealed class HeldSerialLink(InMemorySerialLink inner) : ISerialLink
{
    private TaskCompletionSource _release = new();

    public string Name => inner.Name;

    public bool HasUnreadBytes => inner.HasUnreadBytes;

    /// <summary>Lets the reader go on; <see cref="Hold"/> stops it again before its next read.</summary>
    public void Release() => _release.TrySetResult();

    public void Hold() => _release = new TaskCompletionSource();

    public async ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken)
    {
        await _release.Task.WaitAsync(cancellationToken);
        return await inner.ReadAsync(buffer, cancellationToken);
    }

    public async ValueTask<StampedRead> ReadStampedAsync(Memory<byte> buffer, TimeProvider time, CancellationToken cancellationToken)
    {
        await _release.Task.WaitAsync(cancellationToken);
        return await inner.ReadStampedAsync(buffer, time, cancellationToken);
    }

    public ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken) => inner.WriteAsync(data, cancellationToken);

    public ValueTask DisposeAsync()
    {
        _release.TrySetResult();
        return inner.DisposeAsync();
    }
}
