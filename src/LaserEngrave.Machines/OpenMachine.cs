using LaserEngrave.Devices.Machine;
using LaserEngrave.Simulator.Burn;

namespace LaserEngrave.Machines;

/// <summary>A machine a front end opened (<see cref="MachineFactory"/>): the session it drives and, on the twin, what the twin saw.</summary>
/// <param name="session">The stage, the laser gate and their clock; disposing it closes the twin behind in-process links too.</param>
/// <param name="twin">The twin's inspector; null on real ports.</param>
public sealed class OpenMachine(MachineSession session, ITwinInspector? twin) : IAsyncDisposable
{
    public MachineSession Session => session;

    /// <summary>What the twin saw of the sample (the burn check for the log, pulse maps); null on real ports, where nothing can see the burn.</summary>
    public ITwinInspector? Twin => twin;

    /// <summary>Whether this is the twin rather than real ports.</summary>
    public bool IsSimulated => twin is not null;

    public ValueTask DisposeAsync() => session.DisposeAsync();
}
