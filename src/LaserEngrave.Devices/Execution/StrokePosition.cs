namespace LaserEngrave.Devices.Execution;

/// <summary>Where a timed run's engine puts the stage during a stroke, by its own timing, and which of the pass's moves the stroke runs.</summary>
/// <param name="X">Absolute X, microsteps.</param>
/// <param name="Y">The row's Y, microsteps.</param>
/// <param name="FirstMoveIndex">Index in the pass's moves of the stroke's first move.</param>
/// <param name="MoveCount">How many moves the stroke runs.</param>
public readonly record struct StrokePosition(long X, long Y, long FirstMoveIndex, int MoveCount);
