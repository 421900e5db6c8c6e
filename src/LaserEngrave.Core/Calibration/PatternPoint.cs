namespace LaserEngrave.Core.Calibration;

/// <summary>A point of the calibration pattern in job coordinates, mm from the job's top-left corner (x right, y down = stage +Y).</summary>
public readonly record struct PatternPoint(double XMm, double YMm);
