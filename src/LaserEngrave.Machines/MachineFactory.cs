using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Machine;
using LaserEngrave.Simulator;

namespace LaserEngrave.Machines;

/// <summary>Opens the machine a front end asks for, composed above both the host's devices and the twin (neither knows the other).</summary>
public static class MachineFactory
{
    /// <summary>A twin on in-memory links with the host's stage and gate already on them; the session's <see cref="MachineSession.Owner"/> is the twin, disposed with it.</summary>
    public static MachineSession OpenTwin(MachineProfile profile, SimulatorOptions? options = null)
    {
        var machine = SimulatedMachine.CreateInProcess(profile, options);
        return MachineSession.OverLinks(machine.StageLink, machine.LaserLink, profile, machine.TimeProvider, "simulator", owner: machine);
    }
}
