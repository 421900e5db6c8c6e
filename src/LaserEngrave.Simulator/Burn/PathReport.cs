namespace LaserEngrave.Simulator.Burn;

/// <summary>What the twin measured of a vector job's pulses against its paths (docs/vectors.md).</summary>
/// <param name="Pulses">Pulses fired in the window.</param>
/// <param name="DeviationMeanUm">Mean distance of a pulse's centre from the nearest path, µm.</param>
/// <param name="DeviationMaxUm">Largest such distance, µm.</param>
/// <param name="SpacingMinUm">Smallest distance between consecutive pulses of one laser-on stretch, its first and last 10 µm left out, µm.</param>
/// <param name="SpacingMeanUm">Mean of those distances, µm.</param>
/// <param name="SpacingMaxUm">Largest of those distances, µm.</param>
/// <param name="ExpectedSpacingUm">The burn speed over the pulse frequency, µm.</param>
/// <param name="DwellCount">Stretches of pulses fired with the stage below a tenth of the burn speed.</param>
/// <param name="DwellPulses">Pulses in those stretches.</param>
/// <param name="OffPathPulses">Pulses further than <see cref="PathAnalysis.OffPathUm"/> from every path.</param>
/// <param name="LaserOnSeconds">Total time the laser fired.</param>
public sealed record PathReport(
    long Pulses,
    double DeviationMeanUm,
    double DeviationMaxUm,
    double SpacingMinUm,
    double SpacingMeanUm,
    double SpacingMaxUm,
    double ExpectedSpacingUm,
    int DwellCount,
    long DwellPulses,
    long OffPathPulses,
    double LaserOnSeconds);
