using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.Devices.Execution;

/// <summary>The machine an <see cref="EngraveSession"/> runs on: the devices, their clock, and how the log names them.</summary>
/// <param name="Stage">Both axes.</param>
/// <param name="Gate">The laser gate.</param>
/// <param name="TimeProvider">The clock every wait uses (the simulator's, possibly virtual, or the system's).</param>
/// <param name="StagePort">The stage's port, as the log names it.</param>
/// <param name="LaserPort">The laser gate's port, as the log names it.</param>
public sealed record EngraveMachine(IStage Stage, ILaserGate Gate, TimeProvider TimeProvider, string StagePort, string LaserPort)
{
    /// <summary>Whether this is the simulator (the log says so).</summary>
    public bool Simulated { get; init; }

    /// <summary>Checks the burn after the run (the simulator's burn recorder); null on a real machine.</summary>
    public IRunInspector? Inspector { get; init; }
}
