namespace LaserEngrave.Core.Jobs;

/// <summary>Where a run that did not complete stopped: the first move not completed and the stage's last known position.</summary>
/// <param name="Row">The image row of the first move not completed (0 = top row).</param>
/// <param name="MoveIndex">Its index in the plan's moves (<see cref="Planning.RasterPlan.Moves()"/>); a resumed run starts here.</param>
/// <param name="XMicrosteps">Stage X when it stopped, microsteps; null when unknown.</param>
/// <param name="YMicrosteps">Stage Y when it stopped, microsteps; null when unknown.</param>
public sealed record RunStopPoint(int Row, long MoveIndex, long? XMicrosteps = null, long? YMicrosteps = null);
