using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Process;

/// <summary>Seed 004's pulse arithmetic: what a pulsed laser leaves along a line scanned at a speed, and the inverse.</summary>
/// <remarks>
/// A laser firing at f Hz while the spot moves at v leaves one pulse every D = v / f along the line (the pulse spacing).
/// Pulses overlap by 1 - D / spot (negative: gaps between them). A pixel of pitch p gets p / D pulses, N p / D when every
/// dot gets N pulses. The speed for a wanted spacing is v = D f / N (seed 004: 0.1 mm x 60 kHz / 1 = 6 m/s).
/// Units are in the names: mm/s, Hz, µm, µJ.
/// </remarks>
public static class PulseArithmetic
{
    /// <summary>Distance between two successive pulses, µm: D = v / f.</summary>
    public static double SpacingUm(double speedMmPerS, double frequencyHz, int pulsesPerDot = 1) =>
        Units.MmToUm(speedMmPerS) * pulsesPerDot / frequencyHz;

    /// <summary>Speed that places dots <paramref name="spacingUm"/> apart with <paramref name="pulsesPerDot"/> pulses each, mm/s: v = D f / N.</summary>
    public static double SpeedMmPerS(double spacingUm, double frequencyHz, int pulsesPerDot = 1) =>
        Units.UmToMm(spacingUm) * frequencyHz / pulsesPerDot;

    /// <summary>Frequency that places dots <paramref name="spacingUm"/> apart at <paramref name="speedMmPerS"/>, Hz: f = v N / D.</summary>
    public static double FrequencyHz(double speedMmPerS, double spacingUm, int pulsesPerDot = 1) =>
        Units.MmToUm(speedMmPerS) * pulsesPerDot / spacingUm;

    /// <summary>Pulses per dot that a speed, frequency and dot spacing imply: N = D f / v (not necessarily whole).</summary>
    public static double PulsesPerDot(double speedMmPerS, double frequencyHz, double spacingUm) =>
        spacingUm * frequencyHz / Units.MmToUm(speedMmPerS);

    /// <summary>Overlap of successive pulses as a fraction: 1 - D / spot (0 = just touching, negative = gaps).</summary>
    public static double Overlap(double spacingUm, double spotDiameterUm) => 1 - (spacingUm / spotDiameterUm);

    /// <summary>The spacing that gives an overlap (a fraction, below 1), µm: D = spot (1 - overlap).</summary>
    public static double SpacingForOverlap(double overlap, double spotDiameterUm) => spotDiameterUm * (1 - overlap);

    /// <summary>Pulses that land within one pixel of <paramref name="pitchUm"/>: N p / D.</summary>
    public static double PulsesPerPixel(double pitchUm, double spacingUm, int pulsesPerDot = 1) => pitchUm * pulsesPerDot / spacingUm;

    /// <summary>Length of one unit of a grid that divides <paramref name="fieldMm"/> into <paramref name="units"/> steps, µm (seed 004: 110 mm / 65536 = 1.68 µm).</summary>
    public static double GridUnitUm(double fieldMm, long units) => Units.MmToUm(fieldMm) / units;

    /// <summary>A distance in whole grid units, rounded half away from zero (seed 004: 100 µm at 1.68 µm = 59.6, so 60 units).</summary>
    public static long ToGridUnits(double distanceUm, double unitUm) => (long)Math.Round(distanceUm / unitUm, MidpointRounding.AwayFromZero);
}
