using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Replay;
using LaserEngrave.Testing;
using NSubstitute;

namespace LaserEngrave.App.Tests.Services;

/// <summary>A run the app starts on real ports keeps its flight recorder beside its log, as the command line's does (issue 22, item 5).</summary>
public sealed class AppRunRecordingTests : IDisposable
{
    private readonly TestFiles.TempFolder _folder = TestFiles.NewFolder();

    public void Dispose() => _folder.Dispose();

    [Fact(Timeout = 180_000)]
    public async Task Start_OnPorts_TheRunIsRecordedBesideItsLogAndItsReplayBurnsWhatTheSimulatorBurned()
    {
        var ct = TestContext.Current.CancellationToken;
        var profile = MachineProfile.Default;
        await using var stage = await SocatPtyPair.StartAsync(ct);
        await using var laser = await SocatPtyPair.StartAsync(ct);

        // The simulator on the ports' other ends, in this process so that its own burn can be read; 1 mm from home so homing takes a moment.
        var simulator = SimulatedMachine.Attach(
            SerialPortLink.Open(stage.A, profile.StageBaudRate), SerialPortLink.Open(laser.A, profile.Gate.BaudRate), profile, new SimulatorOptions { StartMm = 1 });
        var logs = new RunLogFolder(Path.Combine(_folder.Path, "logs"));
        var activity = new MachineActivity();
        var machine = new MachineViewModel(new MachineConnectionFactory(), profile, activity) { UseSimulator = false, StagePort = stage.B, LaserPort = laser.B };
        var job = new JobViewModel(new ImageService(), profile, activity);
        var log = new LogViewModel(logs, Substitute.For<IFileAccess>(), job);
        var run = new RunViewModel(new EngraveRunService(), job, machine, log, TimeProvider.System);
        BurnReport simulated;
        RunRecord record;
        string logPath;
        await using (simulator)
        {
            job.LoadImage(TestFiles.WriteChecker(_folder.Path, 6, 3, cell: 1));
            job.EditWidth(0.6);
            job.OriginXMm = 1;
            job.OriginYMm = 1;

            // Step by step (paper), as the other ports runs: on a loaded test machine the wall-clock simulator shifts by more than any latency model.
            job.Strategy = PlanStrategy.Paper;
            await machine.ConnectCommand.ExecuteAsync(null);
            Assert.True(run.StartCommand.CanExecute(null), run.Error ?? machine.Error);

            // A test move before the run: the connection lives on, and only the run is recorded.
            await machine.HomeCommand.ExecuteAsync(null);
            var inspector = new BurnInspector(simulator);
            inspector.Begin();
            await run.StartCommand.ExecuteAsync(null);

            Assert.True(run.State == RunState.Completed, run.Error);
            var entry = Assert.Single(logs.History());
            logPath = entry.Path;
            record = RunLogStore.Read(logPath);
            inspector.Inspect(PreparedJob.Prepare(RunReplay.ToJobSpec(record)));
            simulated = inspector.Report!;
            await machine.DisconnectCommand.ExecuteAsync(null);
        }

        var recording = Assert.IsType<RunRecording>(record.Recording);
        Assert.False(recording.Truncated);
        var wire = Path.Combine(logs.Folder, recording.File);
        Assert.StartsWith("wire_", recording.File, StringComparison.Ordinal);
        var events = WireRecording.Read(wire);
        Assert.Equal(recording.Events, events.Count);

        var spec = RunReplay.ToJobSpec(record);
        var (replayed, burn) = await RecordedRunReplay.ReplayAsync(
            PreparedJob.Prepare(spec), spec.Profile, events, RecordedRunReplay.Setup(record, spec.Profile, events, new SimulatorOptions()), ct);

        TestContext.Current.TestOutputHelper?.WriteLine($"simulator: {simulated.Pulses} pulses, missing {simulated.MissingPixels}, extra {simulated.ExtraPixels}, on white {simulated.LaserOnTravelCount}\nreplay: {replayed}");
        Assert.Equal((simulated.MissingPixels, simulated.ExtraPixels, (long)simulated.LaserOnTravelCount), (replayed.MissingPixels, replayed.ExtraPixels, replayed.LaserOnTravelCount));
        Assert.True(simulated.Burned.ContentEquals(burn!.Burned), "the replay's burned pixels differ from the simulator's");
    }
}
