using System.Text.Json;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Testing;

namespace LaserEngrave.Cli.Tests;

/// <summary>`engrave` on ports records its bytes; `replay LOG` burns them through the twin (issue 22, item 5).</summary>
public sealed class ReplayCommandTests : IDisposable
{
    private readonly string _logDir = Directory.CreateTempSubdirectory("le-cli-replay-").FullName;

    public void Dispose() => Directory.Delete(_logDir, recursive: true);

    [Fact(Timeout = 180_000)]
    public async Task ReplayOfAPortsRun_BurnsWhatTheSimulatorOnThePortsBurned()
    {
        var ct = TestContext.Current.CancellationToken;
        var profile = MachineProfile.Default;
        await using var stage = await SocatPtyPair.StartAsync(ct);
        await using var laser = await SocatPtyPair.StartAsync(ct);

        // The simulator on the ports' other ends, in this process so that its own burn can be read; 1 mm from home as
        // `laserengrave simulator` is in the other ports tests, so that homing takes a moment.
        var simulator = SimulatedMachine.Attach(
            SerialPortLink.Open(stage.A, profile.StageBaudRate), SerialPortLink.Open(laser.A, profile.Gate.BaudRate), profile, new SimulatorOptions { StartMm = 1 });
        BurnReport simulated;
        string logPath;
        await using (simulator)
        {
            var inspector = new BurnInspector(simulator);
            inspector.Begin();
            var image = Path.Combine(_logDir, "small.pbm");
            await File.WriteAllTextAsync(image, "P1\n6 3\n1 1 0 0 1 1\n0 1 1 1 1 0\n1 0 1 0 1 0\n", ct);

            // Step by step (paper), as the other ports runs: on a loaded test machine the wall-clock simulator shifts by more than any latency model.
            var (exit, output, error) = await CliHarness.RunAsync(
                "engrave", image, "--width-mm", "0.6", "--origin-mm", "1,1", "--strategy", "paper", "--stage-port", stage.B, "--laser-port", laser.B, "--json", "--log-dir", _logDir);

            Assert.True(exit == 0, error);
            using var json = JsonDocument.Parse(output);
            logPath = json.RootElement.GetProperty("logPath").GetString()!;
            var record = RunLogStore.Read(logPath);
            var recording = Assert.IsType<RunRecording>(record.Recording);
            Assert.False(recording.Truncated);
            Assert.True(File.Exists(Path.Combine(_logDir, recording.File)));
            inspector.Inspect(PreparedJob.Prepare(RunReplay.ToJobSpec(record)));
            simulated = inspector.Report!;
        }

        var burned = Path.Combine(_logDir, "replayed.png");
        var (replayExit, replayOutput, replayError) = await CliHarness.RunAsync("replay", logPath, "--json", "--burned", burned);

        Assert.True(replayExit == 0, replayError);
        using var replay = JsonDocument.Parse(replayOutput);
        var r = replay.RootElement;
        TestContext.Current.TestOutputHelper?.WriteLine($"simulator: {simulated.Pulses} pulses, missing {simulated.MissingPixels}, extra {simulated.ExtraPixels}, on white {simulated.LaserOnTravelCount}\nreplay: {replayOutput}");
        Assert.Equal(
            (simulated.MissingPixels, simulated.ExtraPixels, (long)simulated.LaserOnTravelCount),
            (r.GetProperty("missingPixels").GetInt64(), r.GetProperty("extraPixels").GetInt64(), r.GetProperty("laserOnTravelCount").GetInt64()));
        var simulatedPng = new MemoryStream();
        simulated.WritePng(simulatedPng);
        Assert.Equal(simulatedPng.ToArray(), await File.ReadAllBytesAsync(burned, ct));

        // What the recording cannot tell is said apart, in µm and pixels, not added to the pulses on white.
        var uncertainty = r.GetProperty("replay");
        Assert.StartsWith("edges placed within ±", uncertainty.GetProperty("summary").GetString(), StringComparison.Ordinal);
        var figures = uncertainty.GetProperty("figures");
        Assert.InRange(figures.GetProperty("uncertainPixels").GetInt64(), 0, 18);
        Assert.InRange(r.GetProperty("laserOnTravelCount").GetInt64(), figures.GetProperty("pulsesOnWhite").GetProperty("least").GetInt64(), figures.GetProperty("pulsesOnWhite").GetProperty("most").GetInt64());
    }

    [Fact(Timeout = 180_000)]
    public async Task ReplayOfAPortsRunOfLayers_GivesEachLayerThatRanItsOwnFigures()
    {
        var ct = TestContext.Current.CancellationToken;
        var profile = MachineProfile.Default;
        await using var stage = await SocatPtyPair.StartAsync(ct);
        await using var laser = await SocatPtyPair.StartAsync(ct);
        var simulator = SimulatedMachine.Attach(
            SerialPortLink.Open(stage.A, profile.StageBaudRate), SerialPortLink.Open(laser.A, profile.Gate.BaudRate), profile, new SimulatorOptions { StartMm = 1 });
        string logPath;
        await using (simulator)
        {
            await File.WriteAllTextAsync(Path.Combine(_logDir, "small.pbm"), "P1\n6 3\n1 1 0 0 1 1\n0 1 1 1 1 0\n1 0 1 0 1 0\n", ct);
            var job = Path.Combine(_logDir, "job.json");
            await File.WriteAllTextAsync(job, """
                { "layers": [
                  { "name": "left", "source": "small.pbm", "widthMm": 0.6, "originMm": [1, 1] },
                  { "name": "right", "source": "small.pbm", "widthMm": 0.6, "originMm": [2, 1] }
                ] }
                """, ct);

            // On a loaded test machine the wall-clock simulator may stop the run: what ran is replayed either way.
            var (_, output, error) = await CliHarness.RunAsync("engrave", "--job", job, "--stage-port", stage.B, "--laser-port", laser.B, "--json", "--log-dir", _logDir);
            using var json = JsonDocument.Parse(output);
            logPath = json.RootElement.GetProperty("logPath").GetString()!;
            TestContext.Current.TestOutputHelper?.WriteLine(error);
        }

        var record = RunLogStore.Read(logPath);
        var (exit, replayOutput, replayError) = await CliHarness.RunAsync("replay", logPath, "--json");
        var (burnedExit, _, burnedError) = await CliHarness.RunAsync("replay", logPath, "--burned", Path.Combine(_logDir, "b.png"));

        Assert.True(exit == 0, replayError);
        using var replay = JsonDocument.Parse(replayOutput);
        var layers = replay.RootElement.GetProperty("layers").EnumerateArray().ToList();
        Assert.Equal(2, layers.Count);
        for (var i = 0; i < 2; i++)
        {
            // A layer that ran has the replay's figures, one that never started has none.
            var simulation = layers[i].GetProperty("simulation");
            Assert.Equal(record.Layers![i].Outcome is not null, simulation.ValueKind == JsonValueKind.Object);
        }

        Assert.Equal(2, burnedExit);
        Assert.Contains("a job of layers has its figures layer by layer", burnedError, StringComparison.Ordinal);
    }

    [Fact]
    public async Task EngraveOnPortsThatDoNotOpen_LeavesNoRecordingBehind()
    {
        var missing = Path.Combine(_logDir, "no-such-port");

        var (exit, _, error) = await CliHarness.RunAsync(
            "engrave", Path.Combine(CliHarness.RepositoryRoot, "assets", "qr-code.bmp"), "--width-mm", "2", "--stage-port", missing, "--laser-port", missing + "2", "--log-dir", _logDir);

        Assert.NotEqual(0, exit);
        Assert.Contains("no-such-port", error, StringComparison.Ordinal);
        Assert.Empty(Directory.GetFiles(_logDir, "wire_*"));
    }

    [Fact]
    public async Task Replay_ALogWithoutARecording_IsRefusedInOneLine()
    {
        var (exit, output, _) = await CliHarness.RunAsync(
            "engrave", Path.Combine(CliHarness.RepositoryRoot, "assets", "qr-code.bmp"), "--width-mm", "2", "--simulate", "--json", "--log-dir", _logDir);
        Assert.Equal(0, exit);
        using var json = JsonDocument.Parse(output);
        var logPath = json.RootElement.GetProperty("logPath").GetString()!;

        var (replayExit, _, error) = await CliHarness.RunAsync("replay", logPath);

        Assert.Equal(2, replayExit);
        Assert.Contains("the run has no recording", error, StringComparison.Ordinal);
        Assert.Single(error.TrimEnd().Split('\n'));
    }

    [Fact]
    public async Task Replay_ALogWhoseRecordingIsTruncatedOrCut_IsRefusedInOneLine()
    {
        var (exit, output, _) = await CliHarness.RunAsync(
            "engrave", Path.Combine(CliHarness.RepositoryRoot, "assets", "qr-code.bmp"), "--width-mm", "2", "--simulate", "--json", "--log-dir", _logDir);
        Assert.Equal(0, exit);
        using var json = JsonDocument.Parse(output);
        var logPath = json.RootElement.GetProperty("logPath").GetString()!;
        var record = RunLogStore.Read(logPath);
        var cut = Path.Combine(_logDir, "cut.jsonl");
        await File.WriteAllTextAsync(cut, "{\"wire\":1}\n{\"t\":0.1,\"p\":\"s\",\"d\":\"w\",\"x\":\"013200000000\"}\n", TestContext.Current.CancellationToken);
        var truncatedLog = Path.Combine(_logDir, "truncated.json");
        await File.WriteAllTextAsync(truncatedLog, RunRecordJson.Serialize(record with { Recording = new RunRecording("cut.jsonl", 1, Truncated: true) }), TestContext.Current.CancellationToken);
        var cutLog = Path.Combine(_logDir, "cut.json");
        await File.WriteAllTextAsync(cutLog, RunRecordJson.Serialize(record with { Recording = new RunRecording("cut.jsonl", 1, Truncated: false) }), TestContext.Current.CancellationToken);
        var escapeLog = Path.Combine(_logDir, "escape.json");
        await File.WriteAllTextAsync(escapeLog, RunRecordJson.Serialize(record with { Recording = new RunRecording("../cut.jsonl", 1, Truncated: false) }), TestContext.Current.CancellationToken);

        foreach (var (log, expected) in new[] { (truncatedLog, "truncated"), (cutLog, "no end mark"), (escapeLog, "not a file name in the log's folder") })
        {
            var (replayExit, _, error) = await CliHarness.RunAsync("replay", log);

            Assert.Equal(2, replayExit);
            Assert.Contains(expected, error, StringComparison.Ordinal);
            Assert.Single(error.TrimEnd().Split('\n'));
        }
    }
}
