namespace LaserEngrave.Core.Logging;

/// <summary>The twin's figures of a drawing's pulses against its paths (docs/vectors.md).</summary>
/// <param name="DeviationUm">Distance of each pulse's centre from the nearest path, µm.</param>
/// <param name="PulseSpacingUm">Distance between consecutive pulses along a burned path (its first and last 10 µm left out), µm.</param>
/// <param name="ExpectedSpacingUm">The burn speed over the pulse frequency, µm.</param>
/// <param name="OffPathPulses">Pulses further than 5 µm from every path (laser on during travel).</param>
public sealed record PathFigures(MeanMax DeviationUm, SpacingRange PulseSpacingUm, double ExpectedSpacingUm, long OffPathPulses);

/// <summary>A mean and a largest value.</summary>
public sealed record MeanMax(double Mean, double Max);

/// <summary>Smallest, mean and largest value.</summary>
public sealed record SpacingRange(double Min, double Mean, double Max);
