using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Machine;
using LaserEngrave.Devices.Scheduling;
using LaserEngrave.Wire.Scheduling;

namespace LaserEngrave.App.Services;

/// <summary>The command line's <see cref="MachineCheck"/> on the app's connection: the same steps, on the machine's clock.</summary>
public sealed class MachineCheckService : IMachineCheckService
{
    public Task<MachineCheckReport> RunAsync(IMachineConnection connection, MachineProfile profile, double distanceMm, int exchanges, bool tripWatchdog, IProgress<MachineCheckStep> progress, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(connection);
        ArgumentNullException.ThrowIfNull(profile);
        var check = new MachineCheck(connection.Stage, connection.Gate, connection.Latency, profile, connection.TimeProvider, connection.Description);

        // Where the machine's clock says: on the simulation's loop in virtual time.
        return TaskRunner.For(connection.TimeProvider).Run(() => check.RunAsync(distanceMm, exchanges, tripWatchdog, cancellationToken, progress));
    }
}
