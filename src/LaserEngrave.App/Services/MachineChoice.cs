namespace LaserEngrave.App.Services;

/// <summary>Which machine to connect to: the built-in simulator, or the stage and laser gate on two serial ports.</summary>
/// <param name="UseSimulator">The in-process simulated machine, in real time.</param>
/// <param name="StagePort">The Zaber chain's port (e.g. COM3, /dev/ttyUSB0) when not simulated.</param>
/// <param name="LaserPort">The laser gate's port when not simulated.</param>
public sealed record MachineChoice(bool UseSimulator, string? StagePort, string? LaserPort)
{
    public static MachineChoice Simulator { get; } = new(true, null, null);
}
