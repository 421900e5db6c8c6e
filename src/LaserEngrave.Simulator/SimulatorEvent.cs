namespace LaserEngrave.Simulator;

/// <summary>Something a technician watching the simulator wants to know: a link came or went, a fault struck, the watchdog tripped.</summary>
/// <param name="Time">When, on the simulator's clock.</param>
/// <param name="Port">"stage" or "laser".</param>
/// <param name="Message">What happened, one line.</param>
public sealed record SimulatorEvent(DateTimeOffset Time, string Port, string Message)
{
    public override string ToString() => $"{Time:HH:mm:ss.fff} {Port}: {Message}";
}
