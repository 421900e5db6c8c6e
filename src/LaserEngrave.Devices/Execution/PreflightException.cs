using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.Devices.Execution;

/// <summary>Preflight refused to start the run; the message is one line with the reason.</summary>
public sealed class PreflightException : DeviceException
{
    public PreflightException(string message)
        : base(message)
    {
    }

    public PreflightException(string message, Exception inner)
        : base(message, inner)
    {
    }
}
