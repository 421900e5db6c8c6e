namespace LaserEngrave.App.ViewModels;

/// <summary>Where the laser is drawn during a run, microsteps, and the instant that position is for: seconds on the machine's clock (its timestamp).</summary>
/// <remarks>One value, so a reader on another thread never pairs one tick's position with another tick's time.</remarks>
public sealed record PacedLaser(long X, long Y, double AtSeconds);
