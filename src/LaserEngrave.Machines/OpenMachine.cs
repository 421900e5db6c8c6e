using LaserEngrave.Devices.Execution;
using LaserEngrave.Devices.Machine;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Machines;

/// <summary>A machine a front end opened (<see cref="MachineFactory"/>): the session it drives and, on the twin, what the twin saw.</summary>
/// <param name="session">The stage, the laser gate and their clock; disposing it closes the twin behind in-process links too.</param>
/// <param name="twin">The twin's inspector; null on real ports.</param>
/// <param name="recordable">On real ports kept open from run to run, the two links each run's flight recorder is switched into; null otherwise.</param>
public sealed class OpenMachine(MachineSession session, ITwinInspector? twin, (RecordedLink Stage, RecordedLink Laser)? recordable = null) : IAsyncDisposable
{
    public MachineSession Session => session;

    /// <summary>What the twin saw of the sample (the burn check for the log, pulse maps); null on real ports, where nothing can see the burn.</summary>
    public ITwinInspector? Twin => twin;

    /// <summary>The machine a run's session engraves on: the stage and gate, their clock, the ports as the log names them, and on the twin its burn check.</summary>
    public EngraveMachine Engraving => new(session.Stage, session.Gate, session.TimeProvider, session.StagePort, session.LaserPort)
    {
        Simulated = IsSimulated,
        Inspector = twin,
    };

    /// <summary>Whether this is the twin rather than real ports.</summary>
    public bool IsSimulated => twin is not null;

    /// <summary>
    /// On ports opened by <see cref="MachineFactory.OpenRecordablePorts"/>, starts a run's flight recorder in
    /// <paramref name="folder"/> (the run logs' folder, so it is kept with the run's log): every byte in and out with its
    /// time, until the run finishes it (docs/run-log.md). Null where nothing is recorded (the twin, whose burn is checked
    /// directly).
    /// </summary>
    public WireRecorder? StartRecording(string folder)
    {
        if (recordable is not { } links)
        {
            return null;
        }

        // Named as the command line names it, beside the logs, so `laserengrave replay LOG` finds it the same way.
        var recorder = new WireRecorder(Path.Combine(folder, $"wire_{DateTime.UtcNow:yyyy-MM-dd_HHmmss}_{Guid.NewGuid().ToString("N")[..8]}.jsonl"), TimeProvider.System);
        links.Stage.RecordTo(recorder);
        links.Laser.RecordTo(recorder);
        return recorder;
    }

    public ValueTask DisposeAsync() => session.DisposeAsync();
}
