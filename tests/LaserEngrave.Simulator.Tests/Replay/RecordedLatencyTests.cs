using System.Text;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator.LaserGate;
using LaserEngrave.Simulator.Replay;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Scheduling;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Simulator.Tests.Replay;

/// <summary>One-way delays from what a recording shows (issue 34): a round trip the host read late is the host's, not the delivery's.</summary>
public sealed class RecordedLatencyTests : IDisposable
{
    private const double ByteSeconds = 10.0 / 9600;

    private readonly string _folder = Directory.CreateTempSubdirectory("le-latency-").FullName;

    public void Dispose() => Directory.Delete(_folder, recursive: true);

    [Fact]
    public void Estimate_OneReplyReadLateAmongPromptOnes_TheWriteKeepsTheAdaptersDelay()
    {
        // PING every 100 ms; each reply back 2 ms after its round trip on the wire (1 ms each way), but the fifth read 200 ms late.
        var events = new List<WireEvent>();
        var ping = Encoding.ASCII.GetBytes("PING\n");
        var pong = Encoding.ASCII.GetBytes("OK PONG\n");
        for (var i = 0; i < 10; i++)
        {
            var t = i * 0.1;
            var processing = GateFirmwareTiming.ProcessingSeconds(new GateCommandSet(MachineProfile.Default.Gate), ping);
            var back = t + 0.002 + ((ping.Length + pong.Length) * ByteSeconds) + processing + (i == 4 ? 0.2 : 0);
            events.Add(new WireEvent(t, false, true, ping));
            events.Add(new WireEvent(back, false, false, pong));
        }

        var estimate = RecordedLatency.Estimate(MachineProfile.Default, events, command => GateFirmwareTiming.ProcessingSeconds(new GateCommandSet(MachineProfile.Default.Gate), command));

        // Halving the fifth round trip would have delivered its PING 100 ms late.
        var fifth = estimate.Writes[8];
        Assert.Equal(0.001, fifth.Seconds, 9);
        Assert.Equal((0.001, 0.001), (fifth.EarliestSeconds, fifth.LatestSeconds), new ToleranceComparer(1e-9));
        Assert.Equal((1, 0.2), (estimate.Gate.RepliesReadLate, Math.Round(estimate.Gate.LongestReadLateSeconds, 6)));
        Assert.All(estimate.Writes.Where((_, i) => events[i].Write), w => Assert.Equal(0.001, w.Seconds, 9));
    }

    [Theory(Timeout = 60_000)]
    [InlineData(0, 0.0)]
    [InlineData(30, 0.0)]
    [InlineData(30, 0.5)]
    public async Task Replay_ScheduledBurstsTheirRepliesReadLate_FirstPulsesWhereTheGatesTimerPutThem(int stallMs, double spreadMs)
    {
        // Scheduled bursts (BURST n hz AFTER us): the gate's timer, from the line's arrival, places the first pulse. Every
        // other reply is read stallMs late; the replay must put each first pulse where the run's gate fired it, to what
        // the adapters' spread leaves open.
        var profile = MachineProfile.Default;
        var options = new SimulatorOptions { Seed = 11, AdapterLatency = new Jitter(1, spreadMs) };
        var path = Path.Combine(_folder, "after.wire.jsonl");
        var (fired, recordingStart) = await RecordAsync(profile, options, path, TimeSpan.FromMilliseconds(stallMs));
        var events = WireRecording.Read(path);
        var commands = new GateCommandSet(profile.Gate);
        var delays = RecordedLatency.Estimate(profile, events, command => GateFirmwareTiming.ProcessingSeconds(commands, command));

        await using var replay = SimulatedMachine.CreateInProcess(profile, options with { AdapterLatency = Jitter.None });
        var replayStart = 0.0;
        await WireReplay.RunAsync(replay, events, TestContext.Current.CancellationToken, delays: delays.Seconds(), started: s => replayStart = s);
        var replayed = replay.Recorder.LaserOnIntervals(replay.NowSeconds).Select(p => p.From - replayStart).ToList();

        TestContext.Current.TestOutputHelper?.WriteLine($"twin: {string.Join(", ", fired.Select(f => (f - recordingStart).ToString("0.000000")))}\nreplay: {string.Join(", ", replayed.Select(f => f.ToString("0.000000")))}\ngate: {delays.Gate}");
        Assert.Equal(10, fired.Count);
        Assert.Equal(fired.Count, replayed.Count);
        // Each first pulse lies where the run's gate fired it, or within its line's band around it: exactly so when the
        // adapters are steady, however late the host read.
        var bursts = delays.Writes.Where((_, i) => events[i].Write).ToList();
        for (var i = 0; i < fired.Count; i++)
        {
            var off = (fired[i] - recordingStart) - replayed[i];
            Assert.InRange(off, bursts[i].EarliestSeconds - bursts[i].Seconds - 1e-6, bursts[i].LatestSeconds - bursts[i].Seconds + 1e-6);
        }

        Assert.InRange(bursts.Max(w => w.LatestSeconds - w.EarliestSeconds), Units.MsToSeconds(spreadMs), Units.MsToSeconds(6 * spreadMs) + 1e-6);
        Assert.Equal(stallMs > 0 ? 5 : 0, delays.Gate.RepliesReadLate);
    }

    // Ten scheduled bursts 100 ms apart to the twin's gate through the flight recorder; every other reply read late. The first pulses on the twin's clock, and that clock at the recording's start.
    private static async Task<(List<double> FirstPulses, double RecordingStart)> RecordAsync(MachineProfile profile, SimulatorOptions options, string path, TimeSpan stall)
    {
        await using var machine = SimulatedMachine.CreateInProcess(profile, options);
        var start = 0.0;
        await machine.RunAsync(async () =>
        {
            var time = machine.TimeProvider;
            start = machine.NowSeconds;
            using var recorder = new WireRecorder(path, time);
            var link = recorder.Wrap(new LateEveryOtherRead(machine.LaserLink, time, stall), stage: false);
            _ = TaskRunner.For(time).Start(async () =>
            {
                var buffer = new byte[64];
                try
                {
                    while ((await link.ReadStampedAsync(buffer, time, CancellationToken.None)).Count > 0)
                    {
                    }
                }
                catch (Exception ex) when (ex is ObjectDisposedException or IOException or OperationCanceledException)
                {
                    // The machine closed the link.
                }
            });
            for (var i = 0; i < 10; i++)
            {
                await Task.Delay(TimeSpan.FromMilliseconds(100), time);
                await link.WriteAsync(Encoding.ASCII.GetBytes($"BURST 20 1000 AFTER {3000 + (i * 700)}\n"), CancellationToken.None);
            }

            await Task.Delay(TimeSpan.FromSeconds(1), time);
            recorder.Finish();
        });
        return ([.. machine.Recorder.LaserOnIntervals(machine.NowSeconds).Select(p => p.From)], start);
    }

    /// <summary>A host whose reader wakes late for every other read, stamping the bytes when it does, as a real port's reader does.</summary>
    private sealed class LateEveryOtherRead(ISerialLink inner, TimeProvider time, TimeSpan stall) : ISerialLink
    {
        private int _reads;

        public string Name => inner.Name;

        public bool HasUnreadBytes => inner.HasUnreadBytes;

        public async ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken) => (await ReadStampedAsync(buffer, time, cancellationToken)).Count;

        public async ValueTask<StampedRead> ReadStampedAsync(Memory<byte> buffer, TimeProvider clock, CancellationToken cancellationToken)
        {
            var read = await inner.ReadStampedAsync(buffer, clock, cancellationToken);
            if (read.Count > 0 && ++_reads % 2 == 0 && stall > TimeSpan.Zero)
            {
                await Task.Delay(stall, time, cancellationToken);
                return read with { ArrivalTimestamp = clock.GetTimestamp() };
            }

            return read;
        }

        public ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken) => inner.WriteAsync(data, cancellationToken);

        public ValueTask DisposeAsync() => inner.DisposeAsync();
    }

    private sealed class ToleranceComparer(double tolerance) : IEqualityComparer<(double, double)>
    {
        public bool Equals((double, double) x, (double, double) y) => Math.Abs(x.Item1 - y.Item1) <= tolerance && Math.Abs(x.Item2 - y.Item2) <= tolerance;

        public int GetHashCode((double, double) obj) => 0;
    }
}
