using LaserEngrave.Core.Geometry;

namespace LaserEngrave.App.Services;

/// <summary>Opens machines and lists the serial ports to choose from.</summary>
public interface IMachineConnectionFactory
{
    /// <summary>Opens the chosen machine; throws a one-line <see cref="LaserEngrave.Devices.Abstractions.DeviceException"/> (or port error) when a port cannot be opened.</summary>
    Task<IMachineConnection> ConnectAsync(MachineChoice choice, MachineProfile profile, CancellationToken cancellationToken);

    IReadOnlyList<string> ListPorts();
}
