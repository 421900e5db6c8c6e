namespace LaserEngrave.Devices.LaserGate;

/// <summary>A line from the gate that no command was waiting for (late, duplicated, or noise).</summary>
public sealed class LaserGateLineEventArgs(string line) : EventArgs
{
    public string Line { get; } = line;
}
