using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Devices.Zaber;

/// <summary>A Zaber device refused a command with an Error (255) reply.</summary>
public sealed class ZaberException : DeviceException
{
    public ZaberException(string portName, byte device, ZaberFrame request, int errorCode, string message)
        : base(message)
    {
        PortName = portName;
        Device = device;
        Request = request;
        ErrorCode = errorCode;
    }

    public string PortName { get; }

    public byte Device { get; }

    /// <summary>The command that was refused.</summary>
    public ZaberFrame Request { get; }

    public ZaberCommand Command => Request.Command;

    /// <summary>The data of the Error reply.</summary>
    public int ErrorCode { get; }

    /// <summary>What the error code means, from <see cref="ZaberErrorCodes.Describe"/>.</summary>
    public string Meaning => ZaberErrorCodes.Describe(ErrorCode);
}
