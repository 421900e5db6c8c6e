namespace LaserEngrave.Devices.Abstractions;

/// <summary>Any failure talking to hardware; the message is one line a technician can act on.</summary>
public class DeviceException : Exception
{
    public DeviceException(string message)
        : base(message)
    {
    }

    public DeviceException(string message, Exception inner)
        : base(message, inner)
    {
    }
}

/// <summary>A device did not answer in time.</summary>
public class DeviceTimeoutException : DeviceException
{
    public DeviceTimeoutException(string message)
        : base(message)
    {
    }

    public DeviceTimeoutException(string message, Exception inner)
        : base(message, inner)
    {
    }
}

/// <summary>The port closed or vanished under us.</summary>
public class LinkLostException : DeviceException
{
    public LinkLostException(string message)
        : base(message)
    {
    }

    public LinkLostException(string message, Exception inner)
        : base(message, inner)
    {
    }
}
