namespace LaserEngrave.Simulator.Burn;

/// <summary>One stretch of the laser firing, as the analysis sees it.</summary>
/// <param name="OnSeconds">When the laser switched on: its pulse train is timed from here, even when the analysis window starts later.</param>
/// <param name="FromSeconds">Start of the part inside the analysis window.</param>
/// <param name="ToSeconds">When it switched off, or the end of the analysis.</param>
/// <param name="FrequencyHz">Pulse frequency.</param>
internal readonly record struct LaserPeriod(double OnSeconds, double FromSeconds, double ToSeconds, double FrequencyHz);
