using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Devices.Machine;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Burn;

namespace LaserEngrave.App.Services;

/// <summary>Opens the in-process simulator (virtual time paced to the wall clock, so the page shows a run at the machine's pace) or two real ports.</summary>
/// <param name="simulatorOptions">How the simulator runs; by default paced virtual time. Tests pass unpaced virtual time.</param>
public sealed class MachineConnectionFactory(SimulatorOptions? simulatorOptions = null) : IMachineConnectionFactory
{
    /// <summary>The simulator the app opens: paced virtual time, so the page shows a run at the machine's pace.</summary>
    public static SimulatorOptions DefaultSimulatorOptions { get; } = new() { Paced = true };

    private readonly SimulatorOptions _simulatorOptions = simulatorOptions ?? DefaultSimulatorOptions;

    public Task<IMachineConnection> ConnectAsync(MachineChoice choice, MachineProfile profile, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(choice);
        ArgumentNullException.ThrowIfNull(profile);
        cancellationToken.ThrowIfCancellationRequested();
        if (choice.UseSimulator)
        {
            var description = _simulatorOptions.RealTime ? "simulator (in-process, real time)"
                : _simulatorOptions.Paced ? "simulator (in-process, at the machine's pace)" : "simulator (in-process, virtual time)";
            return Task.FromResult<IMachineConnection>(new Connection(description, profile, SimulatedMachine.OpenInProcess(profile, _simulatorOptions)));
        }

        var stagePort = Required(choice.StagePort, "stage");
        var laserPort = Required(choice.LaserPort, "laser gate");
        return Task.FromResult<IMachineConnection>(OpenPorts(stagePort, laserPort, profile));
    }

    /// <summary>The machine on two real ports opened already, each run recorded by its flight recorder.</summary>
    /// <param name="description">For the page, e.g. "stage COM3, laser COM4".</param>
    /// <param name="stageLink">The stage's link, closed with the connection.</param>
    /// <param name="laserLink">The laser gate's link, closed with the connection.</param>
    /// <param name="profile">The machine.</param>
    private static IMachineConnection OverRecordedLinks(string description, ISerialLink stageLink, ISerialLink laserLink, MachineProfile profile)
    {
        ArgumentNullException.ThrowIfNull(stageLink);
        ArgumentNullException.ThrowIfNull(laserLink);
        var stage = new RecordedLink(stageLink, stage: true);
        var laser = new RecordedLink(laserLink, stage: false);
        return new Connection(description, profile, MachineSession.OverLinks(stage, laser, profile, TimeProvider.System, description, owner: null), stage, laser);
    }

    private static IMachineConnection OpenPorts(string stagePort, string laserPort, MachineProfile profile)
    {
        var stageLink = SerialPortLink.Open(new SerialPortSettings(stagePort) { BaudRate = profile.StageBaudRate });
        ISerialLink laserLink;
        try
        {
            laserLink = SerialPortLink.Open(new SerialPortSettings(laserPort) { BaudRate = profile.Gate.BaudRate });
        }
        catch
        {
            stageLink.DisposeAsync().AsTask().GetAwaiter().GetResult();
            throw;
        }

        return OverRecordedLinks($"stage {stagePort}, laser {laserPort}", stageLink, laserLink, profile);
    }

    public IReadOnlyList<string> ListPorts() => SerialPortNames.List();

    private static string Required(string? port, string what) =>
        string.IsNullOrWhiteSpace(port) ? throw new DeviceException($"no port chosen for the {what}") : port.Trim();

    private sealed class Connection(string description, MachineProfile profile, MachineSession session, RecordedLink? stageLink = null, RecordedLink? laserLink = null) : IMachineConnection
    {
        public string Description => description;

        public MachineProfile Profile => profile;

        public TimeProvider TimeProvider => session.TimeProvider;

        public bool IsSimulated => session.Owner is SimulatedMachine;

        public IStage Stage => session.Stage;

        public ILaserGate Gate => session.Gate;

        public ILatencyProbe Latency { get; } = new LatencyProbe(session.Stage, session.Gate, session.TimeProvider);

        public IRunInspector? Inspector => session.Owner is SimulatedMachine simulator ? new BurnInspector(simulator) : null;

        public WireRecorder? StartRecording(string folder)
        {
            if (stageLink is null || laserLink is null)
            {
                return null;
            }

            // Named as the command line names it, beside the logs, so `laserengrave replay LOG` finds it the same way.
            var recorder = new WireRecorder(Path.Combine(folder, $"wire_{DateTime.UtcNow:yyyy-MM-dd_HHmmss}_{Guid.NewGuid().ToString("N")[..8]}.jsonl"), TimeProvider.System);
            stageLink.RecordTo(recorder);
            laserLink.RecordTo(recorder);
            return recorder;
        }

        public ValueTask DisposeAsync() => session.DisposeAsync();
    }
}
