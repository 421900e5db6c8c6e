using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Machine;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Machines;
using LaserEngrave.Simulator;

namespace LaserEngrave.App.Services;

/// <summary>Opens the in-process simulator (virtual time paced to the wall clock, so the page shows a run at the machine's pace) or two real ports.</summary>
/// <param name="simulatorOptions">How the simulator runs; by default paced virtual time. Tests pass unpaced virtual time.</param>
public sealed class MachineConnectionFactory(SimulatorOptions? simulatorOptions = null) : IMachineConnectionFactory
{
    /// <summary>The simulator the app opens: the front ends' twin (a realistically late host) in paced virtual time, so the page shows a run at the machine's pace.</summary>
    public static SimulatorOptions DefaultSimulatorOptions { get; } = SimulatorOptions.FrontEnd with { Paced = true };

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
            return Task.FromResult<IMachineConnection>(new Connection(description, profile, MachineFactory.OpenTwin(profile, _simulatorOptions)));
        }

        var stagePort = Required(choice.StagePort, "stage");
        var laserPort = Required(choice.LaserPort, "laser gate");
        return Task.FromResult<IMachineConnection>(new Connection($"stage {stagePort}, laser {laserPort}", profile, MachineFactory.OpenRecordablePorts(stagePort, laserPort, profile)));
    }

    public IReadOnlyList<string> ListPorts() => SerialPortNames.List();

    private static string Required(string? port, string what) =>
        string.IsNullOrWhiteSpace(port) ? throw new DeviceException($"no port chosen for the {what}") : port.Trim();

    private sealed class Connection(string description, MachineProfile profile, OpenMachine machine) : IMachineConnection
    {
        public string Description => description;

        public MachineProfile Profile => profile;

        public TimeProvider TimeProvider => machine.Session.TimeProvider;

        public bool IsSimulated => machine.IsSimulated;

        public IStage Stage => machine.Session.Stage;

        public ILaserGate Gate => machine.Session.Gate;

        public ILatencyProbe Latency { get; } = new LatencyProbe(machine.Session.Stage, machine.Session.Gate, machine.Session.TimeProvider);

        public IRunInspector? Inspector => machine.Twin;

        public WireRecorder? StartRecording(string folder) => machine.StartRecording(folder);

        public ValueTask DisposeAsync() => machine.DisposeAsync();
    }
}
