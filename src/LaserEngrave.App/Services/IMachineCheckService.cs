using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Machine;

namespace LaserEngrave.App.Services;

/// <summary>Runs the machine check (`laserengrave machine check`, docs/commissioning.md) on a connected machine; the seam the Commission panel's tests fake.</summary>
public interface IMachineCheckService
{
    /// <summary>Runs every step on <paramref name="connection"/> against <paramref name="profile"/>, telling <paramref name="progress"/> each as it ends; the laser is off at the end whatever happened.</summary>
    /// <param name="distanceMm">How far each axis is moved from home and read back.</param>
    /// <param name="exchanges">Round trips per device for the latencies.</param>
    /// <param name="tripWatchdog">The person confirmed the beam is blocked.</param>
    Task<MachineCheckReport> RunAsync(IMachineConnection connection, MachineProfile profile, double distanceMm, int exchanges, bool tripWatchdog, IProgress<MachineCheckStep> progress, CancellationToken cancellationToken);
}
