namespace LaserEngrave.Devices.Serial;

/// <summary>Stop bits after each character.</summary>
public enum SerialStopBits
{
    One,
    Two,
}
