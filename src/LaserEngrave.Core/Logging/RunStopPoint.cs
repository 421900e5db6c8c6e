namespace LaserEngrave.Core.Logging;

/// <summary>Where a run that did not complete stopped: the first burn run not completed and the stage's last known position.</summary>
/// <param name="Row">The image row of the first burn run not completed (0 = top row).</param>
/// <param name="RunIndex">Its index among the plan's burn runs in plan order (0 = first); resuming starts here.</param>
/// <param name="XMicrosteps">Stage X when it stopped, microsteps; null when unknown.</param>
/// <param name="YMicrosteps">Stage Y when it stopped, microsteps; null when unknown.</param>
public sealed record RunStopPoint(int Row, long RunIndex, long? XMicrosteps = null, long? YMicrosteps = null);
