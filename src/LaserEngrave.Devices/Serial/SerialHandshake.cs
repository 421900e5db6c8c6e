namespace LaserEngrave.Devices.Serial;

/// <summary>Flow control on the line (Zaber T-series and the laser gate use none).</summary>
public enum SerialHandshake
{
    None,

    /// <summary>Hardware flow control with RTS/CTS.</summary>
    RequestToSend,

    /// <summary>Software flow control with XON/XOFF characters (unusable with binary data such as Zaber frames).</summary>
    XOnXOff,
}
