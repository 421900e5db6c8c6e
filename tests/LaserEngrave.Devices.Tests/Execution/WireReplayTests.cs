using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Devices.Machine;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Replay;
using LaserEngrave.Simulator.Timing;

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
        var options = new SimulatorOptions { Seed = seed, HostLateness = late ? HostLateness.Realistic : HostLateness.None };
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
        var error = Assert.Throws<RunLogException>(() => WireRecording.Read(path));
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

        var error = Assert.Throws<RunLogException>(() => WireRecording.Read(path));

        Assert.Contains(expected, error.Message, StringComparison.Ordinal);
        Assert.StartsWith(path, error.Message, StringComparison.Ordinal);
        Assert.DoesNotContain('\n', error.Message);
    }

    private async Task<(RunRecord Record, BurnReport Burn, string Path)> RecordedRunAsync(PreparedJob job, SimulatorOptions options)
    {
        var machine = SimulatedMachine.CreateInProcess(job.Spec.Profile, options);
        var path = Path.Combine(_folder, "run.wire.jsonl");
        using var recorder = new WireRecorder(path, machine.TimeProvider);
        var session = MachineSession.OverLinks(recorder.Wrap(machine.StageLink, stage: true), recorder.Wrap(machine.LaserLink, stage: false), job.Spec.Profile, machine.TimeProvider, "simulator", owner: machine);
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
