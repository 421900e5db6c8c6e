namespace LaserEngrave.Devices.Serial;

/// <summary>How to open a serial port: 9600 baud, 8 data bits, no parity, 1 stop bit, no handshake unless set.</summary>
/// <param name="PortName">COMn on Windows; /dev/ttyUSBn, /dev/ttySn, /dev/cu.* or any path to a tty (ptys included).</param>
public sealed record SerialPortSettings(string PortName)
{
    public int BaudRate { get; init; } = 9600;

    /// <summary>Data bits per character, 5 to 8.</summary>
    public int DataBits { get; init; } = 8;

    public SerialParity Parity { get; init; } = SerialParity.None;

    public SerialStopBits StopBits { get; init; } = SerialStopBits.One;

    public SerialHandshake Handshake { get; init; } = SerialHandshake.None;

    /// <summary>Throws an <see cref="ArgumentException"/> naming the port and the first unusable value.</summary>
    public void Validate()
    {
        if (string.IsNullOrWhiteSpace(PortName))
        {
            throw new ArgumentException("no serial port given", nameof(PortName));
        }

        if (BaudRate <= 0)
        {
            throw new ArgumentException($"{PortName}: baud rate must be above 0 (got {BaudRate})", nameof(BaudRate));
        }

        if (DataBits is < 5 or > 8)
        {
            throw new ArgumentException($"{PortName}: data bits must be 5 to 8 (got {DataBits})", nameof(DataBits));
        }

        if (!Enum.IsDefined(Parity) || !Enum.IsDefined(StopBits) || !Enum.IsDefined(Handshake))
        {
            throw new ArgumentException($"{PortName}: unknown parity, stop bits or handshake value", nameof(PortName));
        }
    }

    public override string ToString() =>
        $"{PortName} {BaudRate} {DataBits}{Parity.ToString()[0]}{(StopBits == SerialStopBits.One ? 1 : 2)} handshake {Handshake}";
}
