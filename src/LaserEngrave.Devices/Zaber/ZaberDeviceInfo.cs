namespace LaserEngrave.Devices.Zaber;

/// <summary>What discovery learned about one device on the chain.</summary>
/// <param name="DeviceNumber">Number on the chain.</param>
/// <param name="Role">"X" or "Y" when the machine profile uses it, otherwise null.</param>
/// <param name="DeviceId">Device type ID (Return Device ID).</param>
/// <param name="FirmwareVersion">Firmware version x 100.</param>
/// <param name="DeviceMode">Device Mode after discovery (after any fix).</param>
/// <param name="SpeedData">Target Speed data (x 9.375 microsteps/s).</param>
/// <param name="AccelerationData">Acceleration data (x 11250 microsteps/s²).</param>
/// <param name="MaximumPosition">Maximum Position, microsteps.</param>
/// <param name="Position">Current position, microsteps.</param>
/// <param name="AutoReplyWasDisabled">Device Mode bit 0 was set when found: the device would not confirm moves.</param>
/// <param name="AutoReplyFixed">Discovery cleared bit 0.</param>
public sealed record ZaberDeviceInfo(
    byte DeviceNumber,
    string? Role,
    int DeviceId,
    int FirmwareVersion,
    int DeviceMode,
    int SpeedData,
    int AccelerationData,
    long MaximumPosition,
    long Position,
    bool AutoReplyWasDisabled,
    bool AutoReplyFixed)
{
    public bool IsHomed => (DeviceMode & ZaberBinaryDevice.HomeStatusBit) != 0;

    public string FirmwareText => $"{FirmwareVersion / 100}.{FirmwareVersion % 100:00}";
}
