using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Devices.Machine;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.App.Services;

/// <summary>An open machine: the stage and the laser gate, closed together.</summary>
public interface IMachineConnection : IAsyncDisposable
{
    /// <summary>For the page, e.g. "simulator" or "stage COM3, laser COM4".</summary>
    string Description { get; }

    MachineProfile Profile { get; }

    /// <summary>The clock the machine lives on: the simulator's (possibly virtual) or the system's.</summary>
    TimeProvider TimeProvider { get; }

    /// <summary>Whether this is the built-in simulator.</summary>
    bool IsSimulated { get; }

    IStage Stage { get; }

    ILaserGate Gate { get; }

    /// <summary>Times round trips to both axes and the gate (the machine check's latencies).</summary>
    ILatencyProbe Latency { get; }

    /// <summary>The simulator's burn check for a run's log; null on a real machine.</summary>
    IRunInspector? Inspector { get; }

    /// <summary>
    /// On real ports, starts a run's flight recorder in <paramref name="folder"/> (the run logs' folder, so it is kept with
    /// the run's log): every byte in and out with its time, until the run finishes it (docs/run-log.md). Null where nothing
    /// is recorded (the simulator, whose burn is checked directly).
    /// </summary>
    WireRecorder? StartRecording(string folder) => null;
}
