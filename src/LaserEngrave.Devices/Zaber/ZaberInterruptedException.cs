using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.Devices.Zaber;

/// <summary>A move was pre-empted by a later motion command (Stop, or another move) on the same device.</summary>
public sealed class ZaberInterruptedException : DeviceException
{
    public ZaberInterruptedException(string message)
        : base(message)
    {
    }
}
