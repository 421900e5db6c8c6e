namespace LaserEngrave.Devices.Serial;

/// <summary>Parity bit of each character.</summary>
public enum SerialParity
{
    None,
    Odd,
    Even,
}
