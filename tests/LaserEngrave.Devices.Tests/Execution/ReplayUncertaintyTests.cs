using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Devices.Machine;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Replay;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>
/// A replay that can be believed (issue 34): twin runs whose host read its replies late (its reader stalled, as a loaded
/// computer's does) are replayed from their recordings alone; where the recording can know, the replay burns the twin's
/// pixels exactly, and where it cannot it says so in µm and pixels, never as pulses on white.
/// </summary>
public sealed class ReplayUncertaintyTests : IDisposable
{
    private readonly string _folder = Directory.CreateTempSubdirectory("le-replay-").FullName;

    public void Dispose() => Directory.Delete(_folder, recursive: true);

    [Theory(Timeout = 300_000)]
    [InlineData(1, 0.05, 12, 0)]
    [InlineData(2, 0.1, 15, 0)]
    [InlineData(3, 0, 0, 200)]
    public async Task Replay_HostReadRepliesLate_SteadyAdapters_BurnsTheTwinsPixelsAndKnowsIt(int seed, double stallProbability, int stallMs, int oneStallMs)
    {
        // Steady adapters (1 ms each way): what the host's late reader added to a round trip is all the recording cannot
        // split, and the replay must not take it for a late delivery.
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions());
        var options = new SimulatorOptions { Seed = seed, AdapterLatency = new Jitter(1, 0) };
        var (record, twin, path) = await RecordedRunAsync(job, options, new LateReader(seed, stallProbability, TimeSpan.FromMilliseconds(stallMs), oneStallMs == 0 ? null : (300, TimeSpan.FromMilliseconds(oneStallMs))));
        var events = WireRecording.Read(path);
        var setup = RecordedRunReplay.Setup(record, job.Spec.Profile, events, options with { Seed = 99 });

        var (replayed, burn, maybe) = await RecordedRunReplay.ReplayWithUncertaintyAsync(job, job.Spec.Profile, events, setup, TestContext.Current.CancellationToken);
        var uncertainty = Assert.IsType<ReplayUncertainty>(maybe);

        TestContext.Current.TestOutputHelper?.WriteLine($"run: {record.Outcome} {record.Fault?.Message}\ntwin: {record.Simulation}\nreplay: {replayed}\n{uncertainty.Summary()}");
        Assert.InRange(record.Simulation!.Pulses, 1000, long.MaxValue);
        var late = uncertainty.Stage.RepliesReadLate + uncertainty.Gate.RepliesReadLate;
        Assert.InRange(late, 1, int.MaxValue);
        Assert.InRange(Math.Max(uncertainty.Stage.LongestReadLateSeconds, uncertainty.Gate.LongestReadLateSeconds), Units.MsToSeconds(Math.Max(stallMs, oneStallMs) - 3), 1);
        Assert.True(twin.Burned.ContentEquals(burn!.Burned), "the replay's burned pixels differ from the twin's");
        var run = record.Simulation!;
        Assert.Equal((run.Pulses, run.LaserOnTravelCount, run.ExtraPixels, run.MissingPixels), (replayed.Pulses, replayed.LaserOnTravelCount, replayed.ExtraPixels, replayed.MissingPixels));
        Assert.Equal(run.Edges!.MaxErrorUm, replayed.Edges!.MaxErrorUm, 0.005);
        Assert.Equal((0L, 0), (uncertainty.UncertainPixels!.Value, uncertainty.UncertainEdges));
    }

    [Theory(Timeout = 300_000)]
    [InlineData(4)]
    [InlineData(5)]
    public async Task Replay_HostReadRepliesLate_JitteryAdapters_EveryPixelItGetsWrongItCallsUncertain(int seed)
    {
        // The twin's own adapters, 1 ± 0.5 ms each way: a round trip no longer says how it split, so the replay cannot
        // be exact; it must say where it may be wrong, and put on white no pulse that the bands do not allow.
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions());
        var options = new SimulatorOptions { Seed = seed };
        var (record, twin, path) = await RecordedRunAsync(job, options, new LateReader(seed, 0.05, TimeSpan.FromMilliseconds(12), null));
        var events = WireRecording.Read(path);
        var setup = RecordedRunReplay.Setup(record, job.Spec.Profile, events, options with { Seed = 99 });

        var (replayed, burn, maybe) = await RecordedRunReplay.ReplayWithUncertaintyAsync(job, job.Spec.Profile, events, setup, TestContext.Current.CancellationToken);
        var uncertainty = Assert.IsType<ReplayUncertainty>(maybe);

        var differing = Differing(twin, burn!);
        TestContext.Current.TestOutputHelper?.WriteLine($"run: {record.Outcome} {record.Fault?.Message}\ntwin: {record.Simulation}\nreplay: {replayed}\n{uncertainty.Summary()}\npixels differing from the twin: {differing}");
        Assert.InRange(uncertainty.Stage.RepliesReadLate + uncertainty.Gate.RepliesReadLate, 1, int.MaxValue);
        Assert.InRange(uncertainty.Positions.Corrected, 1, int.MaxValue);
        Assert.InRange(uncertainty.Positions.WorstOffUm, 0, 1);
        Assert.InRange(uncertainty.EdgesWithinUm, 0.05, 3);
        Assert.InRange(differing, 0, uncertainty.UncertainPixels!.Value);
        Assert.InRange(record.Simulation!.LaserOnTravelCount, uncertainty.PulsesOnWhite.Least, uncertainty.PulsesOnWhite.Most);
        Assert.InRange(replayed.LaserOnTravelCount, uncertainty.PulsesOnWhite.Least, uncertainty.PulsesOnWhite.Most);
    }

    private static long Differing(BurnReport a, BurnReport b)
    {
        long count = 0;
        for (var y = 0; y < a.Burned.Height; y++)
        {
            for (var x = 0; x < a.Burned.Width; x++)
            {
                count += a.Burned[x, y] != b.Burned[x, y] ? 1 : 0;
            }
        }

        return count;
    }

    private async Task<(RunRecord Record, BurnReport Burn, string Path)> RecordedRunAsync(PreparedJob job, SimulatorOptions options, LateReader late)
    {
        var profile = job.Spec.Profile;
        var machine = SimulatedMachine.CreateInProcess(profile, options);
        var path = Path.Combine(_folder, "run.wire.jsonl");
        using var recorder = new WireRecorder(path, machine.TimeProvider);

        // The late reader sits under the recorder: its stamps are what the run's host would have recorded.
        var session = MachineSession.OverLinks(
            recorder.Wrap(late.Wrap(machine.StageLink, machine.TimeProvider), stage: true),
            recorder.Wrap(late.Wrap(machine.LaserLink, machine.TimeProvider), stage: false),
            profile,
            machine.TimeProvider,
            "simulator",
            owner: machine);
        await using (session)
        {
            var inspector = new BurnInspector(machine);
            var log = new RecordingLog();
            var run = new EngraveSession(
                new EngraveMachine(session.Stage, session.Gate, session.TimeProvider, "simulator", "simulator") { Simulated = true, Inspector = inspector },
                job,
                new EngraveSessionOptions { Log = log, Recorder = recorder });
            await run.RunAsync(null, TestContext.Current.CancellationToken);
            return (Assert.Single(log.Records), inspector.Report!, path);
        }
    }

    /// <summary>
    /// A host whose reader thread is sometimes not scheduled when its bytes arrive: it returns them (and stamps them, as
    /// a real port's reader does) <c>stall</c> later, with a probability a read, and once <c>one.Stall</c> late at read
    /// number <c>one.At</c>. Bytes that arrived meanwhile are stamped when it woke.
    /// </summary>
    private sealed class LateReader(int seed, double probability, TimeSpan stall, (int At, TimeSpan Stall)? one)
    {
        private readonly Random _random = new(seed);
        private int _reads;

        public ISerialLink Wrap(ISerialLink link, TimeProvider time) => new Link(link, time, this);

        private TimeSpan NextStall()
        {
            var read = ++_reads;
            if (one is { } o && read == o.At)
            {
                return o.Stall;
            }

            return _random.NextDouble() < probability ? stall : TimeSpan.Zero;
        }

        private sealed class Link(ISerialLink inner, TimeProvider time, LateReader reader) : ISerialLink
        {
            private long _awakeAt = long.MinValue;

            public string Name => inner.Name;

            public bool HasUnreadBytes => inner.HasUnreadBytes;

            public async ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken) =>
                (await ReadStampedAsync(buffer, time, cancellationToken)).Count;

            public async ValueTask<StampedRead> ReadStampedAsync(Memory<byte> buffer, TimeProvider clock, CancellationToken cancellationToken)
            {
                var read = await inner.ReadStampedAsync(buffer, clock, cancellationToken);
                if (read.Count > 0 && reader.NextStall() is { Ticks: > 0 } stall)
                {
                    await Task.Delay(stall, time, cancellationToken);
                    _awakeAt = clock.GetTimestamp();
                }

                return read with { ArrivalTimestamp = Math.Max(read.ArrivalTimestamp, _awakeAt) };
            }

            public ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken) => inner.WriteAsync(data, cancellationToken);

            public ValueTask DisposeAsync() => inner.DisposeAsync();
        }
    }
}
