using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Machine;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Machines;

/// <summary>
/// Opens the machine a front end asks for, real ports or the twin, composed above both the host's devices and the twin
/// (neither knows the other); the command line and the app open every machine here.
/// </summary>
public static class MachineFactory
{
    /// <summary>Two serial ports at the profile's baud rates (<see cref="MachineSession.OpenPorts"/>); no twin looks on.</summary>
    /// <param name="recorder">The flight recorder both links write through; null records nothing.</param>
    public static OpenMachine OpenPorts(string stagePort, string laserPort, MachineProfile profile, WireRecorder? recorder = null) =>
        new(MachineSession.OpenPorts(stagePort, laserPort, profile, recorder), null);

    /// <summary>
    /// Two serial ports kept open from run to run (the app's machine), each run recorded by its own flight recorder
    /// (<see cref="OpenMachine.StartRecording"/>).
    /// </summary>
    public static OpenMachine OpenRecordablePorts(string stagePort, string laserPort, MachineProfile profile)
    {
        var (stageLink, laserLink) = MachineSession.OpenLinks(stagePort, laserPort, profile);
        var stage = new RecordedLink(stageLink, stage: true);
        var laser = new RecordedLink(laserLink, stage: false);
        var description = $"stage {stagePort}, laser {laserPort}";
        return new OpenMachine(MachineSession.OverLinks(stage, laser, profile, TimeProvider.System, description, owner: null), null, (stage, laser));
    }

    /// <summary>A twin on in-memory links with the host's stage and gate already on them; the session's <see cref="MachineSession.Owner"/> is the twin, disposed with it.</summary>
    /// <param name="options">The twin's options; the defaults when null.</param>
    /// <param name="wirePath">A new file the twin's wire traffic is recorded to, on its clock (to compare builds); null records nothing.</param>
    public static OpenMachine OpenTwin(MachineProfile profile, SimulatorOptions? options = null, string? wirePath = null)
    {
        var machine = SimulatedMachine.CreateInProcess(profile, options);
        var recorder = wirePath is null ? null : new WireRecorder(wirePath, machine.TimeProvider, long.MaxValue);
        var session = MachineSession.OverLinks(machine.StageLink, machine.LaserLink, profile, machine.TimeProvider, "simulator", owner: machine, recorder);
        return new OpenMachine(session, new BurnInspector(machine));
    }
}
