using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.LaserGate;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Devices.Zaber;
using LaserEngrave.Simulator;

namespace LaserEngrave.App.Services;

/// <summary>Opens the in-process simulator (real time, so the page shows a run at the machine's pace) or two real ports.</summary>
/// <param name="simulatorOptions">How the simulator runs; by default in real time. Tests pass virtual time.</param>
public sealed class MachineConnectionFactory(SimulatorOptions? simulatorOptions = null) : IMachineConnectionFactory
{
    private readonly SimulatorOptions _simulatorOptions = simulatorOptions ?? new SimulatorOptions { RealTime = true };

    public Task<IMachineConnection> ConnectAsync(MachineChoice choice, MachineProfile profile, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(choice);
        ArgumentNullException.ThrowIfNull(profile);
        cancellationToken.ThrowIfCancellationRequested();
        if (choice.UseSimulator)
        {
            var machine = SimulatedMachine.CreateInProcess(profile, _simulatorOptions);
            var chain = new ZaberChain(new ZaberConnection(machine.StageLink, machine.TimeProvider), profile);
            var gate = new PicLaserGate(machine.LaserLink, profile.Gate, machine.TimeProvider);
            return Task.FromResult<IMachineConnection>(new Connection(_simulatorOptions.RealTime ? "simulator (in-process, real time)" : "simulator (in-process, virtual time)", profile, chain, gate, machine));
        }

        var stagePort = Required(choice.StagePort, "stage");
        var laserPort = Required(choice.LaserPort, "laser gate");
        var stage = ZaberChain.Open(stagePort, profile);
        try
        {
            var gate = PicLaserGate.Open(laserPort, profile.Gate);
            return Task.FromResult<IMachineConnection>(new Connection($"stage {stagePort}, laser {laserPort}", profile, stage, gate, null));
        }
        catch
        {
            stage.DisposeAsync().AsTask().GetAwaiter().GetResult();
            throw;
        }
    }

    public IReadOnlyList<string> ListPorts() => SerialPortNames.List();

    private static string Required(string? port, string what) =>
        string.IsNullOrWhiteSpace(port) ? throw new DeviceException($"no port chosen for the {what}") : port.Trim();

    private sealed class Connection(string description, MachineProfile profile, ZaberChain stage, PicLaserGate gate, SimulatedMachine? machine) : IMachineConnection
    {
        public string Description => description;

        public MachineProfile Profile => profile;

        public TimeProvider TimeProvider => machine?.TimeProvider ?? TimeProvider.System;

        public bool IsSimulated => machine is not null;

        public IStage Stage => stage;

        public ILaserGate Gate => gate;

        public async ValueTask DisposeAsync()
        {
            await gate.DisposeAsync().ConfigureAwait(false);
            await stage.DisposeAsync().ConfigureAwait(false);
            if (machine is not null)
            {
                await machine.DisposeAsync().ConfigureAwait(false);
            }
        }
    }
}
