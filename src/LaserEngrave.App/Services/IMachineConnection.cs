using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.App.Services;

/// <summary>An open machine: the stage and the laser gate, closed together.</summary>
public interface IMachineConnection : IAsyncDisposable
{
    /// <summary>For the page, e.g. "simulator" or "stage COM3, laser COM4".</summary>
    string Description { get; }

    MachineProfile Profile { get; }

    IStage Stage { get; }

    ILaserGate Gate { get; }
}
