namespace LaserEngrave.Core.Alignment;

/// <summary>
/// A mark on the sample: where it is in the job (mm from the job's top-left corner, x right, y down the image) and the
/// stage position, mm, at which the technician found it under the crosshair.
/// </summary>
public readonly record struct Fiducial(double JobXMm, double JobYMm, double StageXMm, double StageYMm);
