using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Process;

/// <summary>What one set of process values does to the material: spacing, overlap, pulses and energy per pixel, and the warnings.</summary>
public sealed record PulseFigures
{
    public required double SpeedMmPerS { get; init; }

    public required double FrequencyHz { get; init; }

    public required int PulsesPerDot { get; init; }

    public required double SpotDiameterUm { get; init; }

    /// <summary>Distance between successive dots (in raster mode, pulses), µm.</summary>
    public required double PulseSpacingUm { get; init; }

    /// <summary>Overlap of successive dots, percent of the spot diameter (negative = gaps).</summary>
    public required double OverlapPercent { get; init; }

    /// <summary>Pixel pitch the figures are for, µm (null: no pixel grid given).</summary>
    public double? PitchUm { get; init; }

    /// <summary>Pulses per pixel (null without a pitch).</summary>
    public double? PulsesPerPixel { get; init; }

    public double? PulseEnergyUj { get; init; }

    /// <summary>Energy delivered per pixel, µJ (null without a pitch and a pulse energy).</summary>
    public double? EnergyPerPixelUj { get; init; }

    public IReadOnlyList<JobWarning> Warnings { get; init; } = [];

    /// <summary>The figures of <paramref name="process"/> for a spot and, when given, a pixel pitch.</summary>
    public static PulseFigures For(ProcessSettings process, double spotDiameterUm, double? pitchUm = null)
    {
        ArgumentNullException.ThrowIfNull(process);
        return For(process.BurnSpeedMmPerS, process.LaserFrequencyHz, spotDiameterUm, pitchUm, process.PulseEnergyUj, process.PulsesPerDot);
    }

    /// <summary>
    /// The figures of dot mode: N pulses at each dot, dots <paramref name="dotSpacingUm"/> apart (the pixel pitch when
    /// every pixel gets one); the speed is the mean speed v = D f / N of seed 004.
    /// </summary>
    public static PulseFigures ForDots(int pulsesPerDot, double frequencyHz, double dotSpacingUm, double spotDiameterUm, double pitchUm, double? pulseEnergyUj = null)
    {
        var perPixel = PulseArithmetic.PulsesPerPixel(pitchUm, dotSpacingUm, pulsesPerDot);
        var warnings = new List<JobWarning>();
        if (dotSpacingUm > spotDiameterUm)
        {
            warnings.Add(new JobWarning(
                JobWarningKind.PulseGaps,
                $"dot spacing {N(dotSpacingUm)} µm is above the {N(spotDiameterUm)} µm spot: the dots leave gaps of {N(dotSpacingUm - spotDiameterUm)} µm"));
        }

        if (perPixel < 1)
        {
            warnings.Add(new JobWarning(
                JobWarningKind.PixelUnderOnePulse,
                $"a {N(pitchUm)} µm pixel gets {N(perPixel)} pulses: some pixels get none"));
        }

        return new PulseFigures
        {
            SpeedMmPerS = PulseArithmetic.SpeedMmPerS(dotSpacingUm, frequencyHz, pulsesPerDot),
            FrequencyHz = frequencyHz,
            PulsesPerDot = pulsesPerDot,
            SpotDiameterUm = spotDiameterUm,
            PulseSpacingUm = dotSpacingUm,
            OverlapPercent = 100 * PulseArithmetic.Overlap(dotSpacingUm, spotDiameterUm),
            PitchUm = pitchUm,
            PulsesPerPixel = perPixel,
            PulseEnergyUj = pulseEnergyUj,
            EnergyPerPixelUj = pulseEnergyUj is { } e ? perPixel * e : null,
            Warnings = warnings,
        };
    }

    /// <summary>The figures of a speed and frequency for a spot and, when given, a pitch and pulse energy.</summary>
    public static PulseFigures For(double speedMmPerS, double frequencyHz, double spotDiameterUm, double? pitchUm = null, double? pulseEnergyUj = null, int pulsesPerDot = 1)
    {
        var spacing = PulseArithmetic.SpacingUm(speedMmPerS, frequencyHz, pulsesPerDot);
        double? perPixel = pitchUm is { } p ? PulseArithmetic.PulsesPerPixel(p, spacing, pulsesPerDot) : null;
        var warnings = new List<JobWarning>();
        if (spacing > spotDiameterUm)
        {
            warnings.Add(new JobWarning(
                JobWarningKind.PulseGaps,
                $"pulse spacing {N(spacing)} µm is above the {N(spotDiameterUm)} µm spot: the pulses leave gaps of {N(spacing - spotDiameterUm)} µm (at most {N(PulseArithmetic.SpeedMmPerS(spotDiameterUm, frequencyHz, pulsesPerDot))} mm/s closes them)"));
        }

        if (perPixel is < 1)
        {
            warnings.Add(new JobWarning(
                JobWarningKind.PixelUnderOnePulse,
                $"a {N(pitchUm!.Value)} µm pixel gets {N(perPixel.Value)} pulses: some pixels get none"));
        }

        return new PulseFigures
        {
            SpeedMmPerS = speedMmPerS,
            FrequencyHz = frequencyHz,
            PulsesPerDot = pulsesPerDot,
            SpotDiameterUm = spotDiameterUm,
            PulseSpacingUm = spacing,
            OverlapPercent = 100 * PulseArithmetic.Overlap(spacing, spotDiameterUm),
            PitchUm = pitchUm,
            PulsesPerPixel = perPixel,
            PulseEnergyUj = pulseEnergyUj,
            EnergyPerPixelUj = perPixel is { } n && pulseEnergyUj is { } e ? n * e : null,
            Warnings = warnings,
        };
    }

    private static string N(double value) => value.ToString("0.###", CultureInfo.InvariantCulture);
}
