namespace LaserEngrave.Core.Logging;

/// <summary>One device a run used, as it identified itself: the firmware version belongs in the lab notebook.</summary>
/// <param name="Role">What it did: "x axis", "y axis" or "laser gate".</param>
/// <param name="Port">The serial port, or "simulator".</param>
/// <param name="Identity">What the device reported: Zaber device ID, the gate's identification line.</param>
/// <param name="Firmware">The firmware version as reported, e.g. "5.29".</param>
public sealed record RunDevice(string Role, string Port, string Identity, string Firmware);
