namespace LaserEngrave.Devices.Execution;

/// <summary>Where a run stopped, and where a new run resumes (<see cref="RunOptions.ResumeFrom"/>).</summary>
/// <param name="Row">Image row of the first move not completed.</param>
/// <param name="MoveIndex">Index in <see cref="Core.Planning.RasterPlan.Moves()"/> of the first move not completed.</param>
/// <param name="XMicrosteps">X where the stage stopped, when it could be read.</param>
/// <param name="YMicrosteps">Y where the stage stopped, when it could be read.</param>
public sealed record RunStopPoint(int Row, long MoveIndex, long? XMicrosteps, long? YMicrosteps);
