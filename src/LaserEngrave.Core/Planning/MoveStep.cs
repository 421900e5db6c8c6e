namespace LaserEngrave.Core.Planning;

/// <summary>A plain move of a step-by-step raster program: the laser switched, the speeds set, both axes to the target, each awaited.</summary>
/// <param name="LaserOn">Whether the laser is on during the move.</param>
/// <param name="X">Target X, microsteps.</param>
/// <param name="Y">Target Y, microsteps.</param>
/// <param name="SpeedData">Target speed data of the axes that move.</param>
/// <param name="Move">The plan's move.</param>
/// <param name="MoveIndex">Its index in the plan's moves.</param>
public readonly record struct MoveStep(bool LaserOn, long X, long Y, int SpeedData, Move Move, long MoveIndex);
