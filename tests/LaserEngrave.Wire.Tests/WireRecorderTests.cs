using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Wire.Tests;

public sealed class WireRecorderTests : IDisposable
{
    private readonly string _folder = Directory.CreateTempSubdirectory("wire-recorder-").FullName;

    public void Dispose() => Directory.Delete(_folder, recursive: true);

    [Fact]
    public async Task WriteAsync_TheOtherPortWritesBetweenAStampAndItsLine_TheRecordingStaysInOrder()
    {
        // A ports run on 2026-11-29 recorded two writes 4 µs out of order (each port's writer on its own thread, the
        // stamp taken before the recorder's lock), and its replay was refused as corrupt. Here the clock itself lets the
        // gate's write through while the stage's write is being stamped: it can only come after the stage's line.
        var clock = new InterleavingClock();
        var path = Path.Combine(_folder, "wire.jsonl");
        var recorder = new WireRecorder(path, clock);
        var (stageHost, _) = InMemorySerialLink.CreatePair("stage");
        var (gateHost, _) = InMemorySerialLink.CreatePair("gate");
        var stage = recorder.Wrap(stageHost, stage: true);
        var gate = recorder.Wrap(gateHost, stage: false);
        clock.Between = () => gate.WriteAsync("OFF\n"u8.ToArray(), CancellationToken.None).AsTask();

        await stage.WriteAsync(new byte[] { 1, 20, 0, 0, 0, 0 }, TestContext.Current.CancellationToken);
        await clock.Other!;
        recorder.Finish();

        var events = WireRecording.Read(path);
        Assert.Equal([true, false], events.Where(e => e.Write).Select(e => e.Stage));
        Assert.True(events[0].Seconds < events[1].Seconds);
    }

    // Steps 1 ms a reading; on the first reading after Between is set it starts Between on another thread and gives it
    // up to a second to finish (it cannot while the recorder holds its lock, and then it does not need to).
    private sealed class InterleavingClock : TimeProvider
    {
        private long _ticks;
        private Func<Task>? _between;

        public Func<Task>? Between { set => _between = value; }

        public Task? Other { get; private set; }

        public override long TimestampFrequency => TimeSpan.TicksPerSecond;

        public override long GetTimestamp()
        {
            var now = Interlocked.Add(ref _ticks, TimeSpan.TicksPerMillisecond);
            if (Interlocked.Exchange(ref _between, null) is { } between)
            {
                Other = Task.Run(between);
                Other.Wait(TimeSpan.FromSeconds(1));
            }

            return now;
        }
    }
}
