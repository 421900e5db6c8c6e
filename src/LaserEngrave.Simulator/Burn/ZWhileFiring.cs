namespace LaserEngrave.Simulator.Burn;

/// <summary>Where the focus axis stood while the laser fired, microsteps, and how many laser-on periods saw it move.</summary>
/// <param name="MinMicrosteps">Lowest Z position at the start or end of a laser-on period.</param>
/// <param name="MaxMicrosteps">Highest such position.</param>
/// <param name="PeriodsWhileMoving">Laser-on periods during which Z was in motion (0 when every focus move was made with the laser off).</param>
/// <param name="Periods">Laser-on periods looked at.</param>
public readonly record struct ZWhileFiring(double MinMicrosteps, double MaxMicrosteps, int PeriodsWhileMoving, int Periods);
