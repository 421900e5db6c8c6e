using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Abstractions;

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

    /// <summary>The simulator's burn check for a run's log; null on a real machine.</summary>
    IRunInspector? Inspector { get; }
}
