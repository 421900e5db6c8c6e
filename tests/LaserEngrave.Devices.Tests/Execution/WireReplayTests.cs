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

/// <summary>The flight recorder and its replay (issue 22, item 5): the host's recorded bytes and times, fed into a fresh twin, burn what the run burned.</summary>
public sealed class WireReplayTests : IDisposable
{
    private readonly string _folder = Directory.CreateTempSubdirectory("le-wire-").FullName;

    public void Dispose() => Directory.Delete(_folder, recursive: true);

    [Theory(Timeout = 300_000)]
    [InlineData(1, false)]
    [InlineData(7, true)]
    public async Task Replay_OfATwinRunsRecording_BurnsExactlyWhatTheTwinBurned(int seed, bool late)
    {
        var job = TestJobs.FromAsset("qr-code.bmp", 5, new PlanOptions());
        // The late host with a gate that has no scheduled bursts: its switch-ons are host-timed, so it has recoveries to replay.
        var options = new SimulatorOptions { Seed = seed, HostLateness = late ? HostLateness.Realistic : HostLateness.None, GateScheduledBursts = !late };
        var (record, twin, path) = await RecordedRunAsync(job, options);

        var events = WireRecording.Read(path);
        await using var replayMachine = SimulatedMachine.CreateInProcess(job.Spec.Profile, options with { HostLateness = HostLateness.None, StartMicrosteps = WireReplay.StartMicrosteps(job.Spec.Profile, events) });
        var inspector = new BurnInspector(replayMachine);
        inspector.Begin();
        await WireReplay.RunAsync(replayMachine, events, TestContext.Current.CancellationToken);
        var replayed = inspector.Inspect(job);

        // The late host's run (seed 7) stopped on a late switch-off until the burst (docs/execution.md): now its late
        // switch-ons are left off and the session goes on from them, and the recoveries' traffic is replayed as well.
        Assert.True(record.Outcome == RunOutcome.Completed, $"{record.Outcome}: {record.Fault?.Message}");
        Assert.True(!late || record.Recoveries is { Count: > 0 }, "the late host's run went on from a late switch-on");
        var recording = Assert.IsType<RunRecording>(record.Recording);
        Assert.Equal((Path.GetFileName(path), false), (recording.File, recording.Truncated));
        Assert.Equal(recording.Events, events.Count);
        TestContext.Current.TestOutputHelper?.WriteLine($"recording {new FileInfo(path).Length} bytes, {events.Count} events\ntwin: {record.Simulation}\nreplay: {replayed}");
        Assert.True(twin.Burned.ContentEquals(inspector.Report!.Burned), "the replay's burned pixels differ from the twin's");
        Assert.Equal(record.Simulation! with { Focus = null }, replayed with { Focus = null });
        Assert.False(replayMachine.Gate.IsFiring);
    }

    [Fact(Timeout = 300_000)]
    public async Task ReplayLayers_OfATwinRunsRecording_EachLayerBurnsExactlyWhatTheTwinBurnedInIt()
    {
        // A raster layer and a drawing of two passes, apart on the stage.
        var job = LayeredJob.Prepare(
            [
                new JobLayer { Name = "logo", Source = TestJobs.AssetPath("qr-code.bmp"), Mode = LayerMode.Raster, WidthMm = 1.5, Origin = new OriginMm(5, 5) },
                new JobLayer { Name = "hexagons", Source = TestJobs.AssetPath(Path.Combine("drawings", "hexagons.dxf")), Mode = LayerMode.Outline, WidthMm = 3, Origin = new OriginMm(10, 5), Passes = 2 },
            ],
            MachineProfile.Default);
        var options = new SimulatorOptions { Seed = 3 };
        var (record, _, path) = await RecordedRunAsync(job, MachineProfile.Default, options);
        var events = WireRecording.Read(path);

        var replayed = await RecordedRunReplay.ReplayLayersAsync(job.Layers, MachineProfile.Default, events, RecordedRunReplay.Setup(record, MachineProfile.Default, events, options, recordedDelays: false), TestContext.Current.CancellationToken);

        Assert.True(record.Outcome == RunOutcome.Completed, record.Fault?.Message);
        Assert.Equal([0, 1], events.Where(e => e.Layer is not null).Select(e => e.Layer!.Value));
        TestContext.Current.TestOutputHelper?.WriteLine($"twin: {string.Join(" | ", record.Layers!.Select(l => l.Simulation))}\nreplay: {string.Join(" | ", replayed)}");
        for (var i = 0; i < 2; i++)
        {
            Assert.Equal(record.Layers![i].Simulation! with { Focus = null }, replayed[i]! with { Focus = null });
        }
    }

    [Fact(Timeout = 300_000)]
    public async Task Replay_RecordedDelays_AdaptersSlowerThanTheTwinsModel_BurnsWhatTheRunBurned()
    {
        // The run's adapters take 3 ms each way where the replaying twin's model says 1 ± 0.5 ms: the delays must come from the recording.
        var profile = MachineProfile.Default with { Latency = MachineProfile.Default.Latency with { StageMs = 3, StageJitterMs = 0.1, GateMs = 3, GateJitterMs = 0.1 } };
        var job = PreparedJob.Prepare(new JobSpec { Profile = profile, ImagePath = TestJobs.AssetPath("qr-code.bmp"), Size = SizeSpec.Width(5), Origin = TestJobs.Origin, Plan = new PlanOptions() });
        var gate = new Jitter(0.5, 0);
        var (record, twin, path) = await RecordedRunAsync(job, new SimulatorOptions { Seed = 5, AdapterLatency = new Jitter(3, 0), GateProcessing = gate });
        var events = WireRecording.Read(path);
        var replayTwin = new SimulatorOptions { Seed = 9, GateProcessing = gate };

        var (recorded, burn) = await RecordedRunReplay.ReplayAsync(job, job.Spec.Profile, events, RecordedRunReplay.Setup(record, job.Spec.Profile, events, replayTwin), TestContext.Current.CancellationToken);
        var (modelled, _) = await RecordedRunReplay.ReplayAsync(job, job.Spec.Profile, events, RecordedRunReplay.Setup(record, job.Spec.Profile, events, replayTwin, recordedDelays: false), TestContext.Current.CancellationToken);

        TestContext.Current.TestOutputHelper?.WriteLine($"run: {record.Simulation}\nrecorded delays: {recorded}\ntwin's model: {modelled}");
        // The run need not complete (3 ms adapters stop it within its first strokes): what it burned is what must come back.
        Assert.InRange(record.Simulation!.Pulses, 1000, long.MaxValue);
        Assert.True(twin.Burned.ContentEquals(burn!.Burned), "the replay's burned pixels differ from the run's");
        var run = record.Simulation!;
        Assert.Equal((run.MissingPixels, run.ExtraPixels, run.LaserOnTravelCount, run.Pulses), (recorded.MissingPixels, recorded.ExtraPixels, recorded.LaserOnTravelCount, recorded.Pulses));
        Assert.Equal(run.Edges!.MeanErrorUm, recorded.Edges!.MeanErrorUm, 0.005);
        Assert.Equal(run.Edges.MaxErrorUm, recorded.Edges.MaxErrorUm, 0.005);

        // The twin's own latency model would have burned something else: the recorded delays are what makes the replay true.
        Assert.NotEqual((run.LaserOnTravelCount, run.ExtraPixels), (modelled.LaserOnTravelCount, modelled.ExtraPixels));
    }

    [Fact]
    public async Task ReplayLayers_ARecordingWithoutLayerStarts_IsRefusedInOneLine()
    {
        var path = Path.Combine(_folder, "old.jsonl");
        await File.WriteAllTextAsync(path, "{\"wire\":1}\n{\"t\":0.1,\"p\":\"s\",\"d\":\"w\",\"x\":\"013200000000\"}\n{\"end\":1}\n", TestContext.Current.CancellationToken);
        var job = LayeredJob.Prepare([new JobLayer { Name = "logo", Source = TestJobs.AssetPath("qr-code.bmp"), Mode = LayerMode.Raster, WidthMm = 1.5, Origin = new OriginMm(5, 5) }], MachineProfile.Default);

        var error = await Assert.ThrowsAsync<RunLogException>(() => RecordedRunReplay.ReplayLayersAsync(job.Layers, MachineProfile.Default, WireRecording.Read(path), new ReplaySetup(new SimulatorOptions(), null), TestContext.Current.CancellationToken));

        Assert.Contains("does not say where each layer began", error.Message, StringComparison.Ordinal);
    }

    [Fact(Timeout = 120_000)]
    public async Task Recorder_AtItsCap_EndsWithTheTruncatedMark_AndReadRefusesIt()
    {
        var path = Path.Combine(_folder, "capped.jsonl");
        var recorder = new WireRecorder(path, TimeProvider.System, capBytes: 200);
        var link = recorder.Wrap(new NullLink(), stage: true);
        for (var i = 0; i < 10; i++)
        {
            await link.WriteAsync(new byte[] { 1, 2, 3, 4, 5, 6 }, TestContext.Current.CancellationToken);
        }

        var summary = recorder.Finish();

        Assert.True(summary.Truncated);
        Assert.InRange(new FileInfo(path).Length, 1, 200);
        var error = Assert.Throws<WireRecordingException>(() => WireRecording.Read(path));
        Assert.Contains("truncated", error.Message, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("{\"wire\":1}\n{\"t\":0.1,\"p\":\"s\",\"d\":\"w\",\"x\":\"0102\"}\n", "no end mark")]
    [InlineData("{\"wire\":1}\n{\"t\":0.1,\"p\":\"s\",\"d\":\"w\",\"x\":\"01Z2\"}\n{\"end\":1}\n", "corrupt")]
    [InlineData("{\"wire\":1}\n{\"t\":0.1,\"p\":\"q\",\"d\":\"w\",\"x\":\"0102\"}\n{\"end\":1}\n", "corrupt")]
    [InlineData("{\"wire\":1}\n{\"t\":0.2,\"p\":\"s\",\"d\":\"w\",\"x\":\"01\"}\n{\"t\":0.1,\"p\":\"s\",\"d\":\"w\",\"x\":\"01\"}\n{\"end\":2}\n", "corrupt")]
    [InlineData("{\"wire\":1}\n{\"t\":0.1,\"p\":\"s\",\"d\":\"w\",\"x\":\"0102\"}\n{\"end\":5}\n", "corrupt")]
    [InlineData("{\"wire\":1}\n{\"t\":NaN,\"p\":\"s\",\"d\":\"w\",\"x\":\"0102\"}\n{\"end\":1}\n", "corrupt")]
    [InlineData("hello\n", "not a LaserEngrave wire recording")]
    public void Read_ABrokenRecording_IsRefusedInOneLine(string text, string expected)
    {
        var path = Path.Combine(_folder, "broken.jsonl");
        File.WriteAllText(path, text);

        var error = Assert.Throws<WireRecordingException>(() => WireRecording.Read(path));

        Assert.Contains(expected, error.Message, StringComparison.Ordinal);
        Assert.StartsWith(path, error.Message, StringComparison.Ordinal);
        Assert.DoesNotContain('\n', error.Message);
    }

    private Task<(RunRecord Record, BurnReport Burn, string Path)> RecordedRunAsync(PreparedJob job, SimulatorOptions options) => RecordedRunAsync(job, job.Spec.Profile, options);

    private async Task<(RunRecord Record, BurnReport Burn, string Path)> RecordedRunAsync(EngraveJob job, MachineProfile profile, SimulatorOptions options)
    {
        var machine = SimulatedMachine.CreateInProcess(profile, options);
        var path = Path.Combine(_folder, "run.wire.jsonl");
        using var recorder = new WireRecorder(path, machine.TimeProvider);
        var session = MachineSession.OverLinks(recorder.Wrap(machine.StageLink, stage: true), recorder.Wrap(machine.LaserLink, stage: false), profile, machine.TimeProvider, "simulator", owner: machine);
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

    private sealed class NullLink : ISerialLink
    {
        public string Name => "null";

        public bool HasUnreadBytes => false;

        public ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken) => ValueTask.FromResult(0);

        public ValueTask<StampedRead> ReadStampedAsync(Memory<byte> buffer, TimeProvider time, CancellationToken cancellationToken) => ValueTask.FromResult(new StampedRead(0, time.GetTimestamp()));

        public ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken) => ValueTask.CompletedTask;

        public ValueTask DisposeAsync() => ValueTask.CompletedTask;
    }
}
