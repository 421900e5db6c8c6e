namespace LaserEngrave.Devices.Zaber;

/// <summary>The devices found on a port and what discovery noticed or fixed, each note one line for a technician.</summary>
public sealed record ZaberDiscovery(string PortName, IReadOnlyList<ZaberDeviceInfo> Devices, IReadOnlyList<string> Notes)
{
    public ZaberDeviceInfo? Find(byte deviceNumber) => Devices.FirstOrDefault(d => d.DeviceNumber == deviceNumber);
}
