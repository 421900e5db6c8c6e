using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.Devices.LaserGate;

/// <summary>The laser gate refused a command (an error reply) or answered something that cannot be understood.</summary>
public sealed class LaserGateException : DeviceException
{
    public LaserGateException(string portName, string command, string reply, string message)
        : base(message)
    {
        PortName = portName;
        Command = command;
        Reply = reply;
    }

    public string PortName { get; }

    /// <summary>The command line sent, without its terminator.</summary>
    public string Command { get; }

    /// <summary>The reply line received.</summary>
    public string Reply { get; }
}
