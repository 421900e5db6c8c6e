namespace LaserEngrave.Core.Planning;

/// <summary>A travel of a timed raster program, laser off: both axes to an absolute target at the travel speed.</summary>
/// <param name="X">Target X, microsteps.</param>
/// <param name="Y">Target Y, microsteps.</param>
/// <param name="SpeedData">Target speed data of the axes that move.</param>
/// <param name="Move">The plan's move (for the accounting of moves done).</param>
/// <param name="MoveIndex">Its index in the plan's moves.</param>
public readonly record struct TravelStep(long X, long Y, int SpeedData, Move Move, long MoveIndex);
