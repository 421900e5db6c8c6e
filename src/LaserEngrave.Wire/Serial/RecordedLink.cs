namespace LaserEngrave.Wire.Serial;

/// <summary>
/// One of a machine's links on real ports, recorded while a run is under way: the app keeps its machine open from run
/// to run, so each run's flight recorder is switched in at its start and finished by the run, as the command line's is.
/// </summary>
/// <remarks>
/// Whether bytes are recorded is decided when they pass (a write when it is made, a read when it returns), not when the
/// reader loop's pending read began, so a recording started while a read waits still has that read's bytes.
/// </remarks>
public sealed class RecordedLink(ISerialLink inner, bool stage) : ISerialLink
{
    private WireRecorder? _recorder;

    public string Name => inner.Name;

    public bool HasUnreadBytes => inner.HasUnreadBytes;

    /// <summary>Records through <paramref name="recorder"/> from now on (null: records nothing); a finished recorder records nothing more.</summary>
    public void RecordTo(WireRecorder? recorder) => Volatile.Write(ref _recorder, recorder);

    public async ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken) =>
        (await ReadStampedAsync(buffer, TimeProvider.System, cancellationToken)).Count;

    public async ValueTask<StampedRead> ReadStampedAsync(Memory<byte> buffer, TimeProvider time, CancellationToken cancellationToken)
    {
        var read = await inner.ReadStampedAsync(buffer, time, cancellationToken);
        if (Volatile.Read(ref _recorder) is { } recorder && read.Count > 0)
        {
            // The recorder's own link records what a read returned: handed the read that has already happened.
            await recorder.Wrap(new Returned(inner, read), stage).ReadStampedAsync(buffer, time, cancellationToken);
        }

        return read;
    }

    public ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken) =>
        Volatile.Read(ref _recorder) is { } recorder ? recorder.Wrap(inner, stage).WriteAsync(data, cancellationToken) : inner.WriteAsync(data, cancellationToken);

    public ValueTask DisposeAsync() => inner.DisposeAsync();

    // A read already made on the real link, returned once more for the recorder to note.
    private sealed class Returned(ISerialLink inner, StampedRead read) : ISerialLink
    {
        public string Name => inner.Name;

        public bool HasUnreadBytes => false;

        public ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken) => ValueTask.FromResult(read.Count);

        public ValueTask<StampedRead> ReadStampedAsync(Memory<byte> buffer, TimeProvider time, CancellationToken cancellationToken) => ValueTask.FromResult(read);

        public ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken) => throw new NotSupportedException();

        public ValueTask DisposeAsync() => ValueTask.CompletedTask;
    }
}
