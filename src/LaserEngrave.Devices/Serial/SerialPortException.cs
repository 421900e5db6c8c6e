using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.Devices.Serial;

/// <summary>A serial port cannot be opened or configured; the message names the port and says what to do.</summary>
public sealed class SerialPortException : DeviceException
{
    public SerialPortException(string portName, string message)
        : base(message)
    {
        PortName = portName;
    }

    public string PortName { get; }
}
