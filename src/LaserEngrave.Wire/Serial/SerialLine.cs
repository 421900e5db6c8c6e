namespace LaserEngrave.Wire.Serial;

/// <summary>The serial line both devices use: 8 data bits, no parity, one stop bit, so a byte takes a start bit, eight
/// data bits and a stop bit on the wire. The one place this number lives: the planners' timing, the estimate, the
/// latency probe and the replay all time bytes by it (a double so that each of their sums stays a floating division).</summary>
public static class SerialLine
{
    /// <summary>Bits a byte takes on the wire (start, 8 data, stop).</summary>
    public const double BitsPerByte = 10;
}
