namespace LaserEngrave.Core.Vectors;

/// <summary>One command of a stroke to one axis, at the time it is to take effect on the device.</summary>
/// <param name="AtSeconds">When its last byte is to arrive at the device, from the stroke's time origin.</param>
/// <param name="Axis">The axis it goes to.</param>
/// <param name="Kind">Move at a constant speed, stop, or a position query.</param>
/// <param name="SpeedData">For <see cref="AxisCommandKind.Speed"/>: the signed speed, Zaber data (x 9.375 microsteps/s).</param>
public readonly record struct AxisCommand(double AtSeconds, VectorAxis Axis, AxisCommandKind Kind, int SpeedData = 0);
