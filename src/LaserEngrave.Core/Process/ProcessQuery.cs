using System.Globalization;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Process;

/// <summary>Some of speed, frequency, spacing (or overlap) and pulses per dot; <see cref="Solve"/> finds the missing one from v = D f / N.</summary>
public sealed record ProcessQuery
{
    /// <summary>Relative difference below which given values count as agreeing.</summary>
    public const double Tolerance = 1e-9;

    public double? SpeedMmPerS { get; init; }

    public double? FrequencyHz { get; init; }

    public double? SpacingUm { get; init; }

    /// <summary>Wanted overlap of successive dots, percent of the spot (below 100); an alternative to <see cref="SpacingUm"/>.</summary>
    public double? OverlapPercent { get; init; }

    /// <summary>Pulses per dot; 1 when not given and not solved for.</summary>
    public int? PulsesPerDot { get; init; }

    public double SpotDiameterUm { get; init; } = 20;

    public double? PitchUm { get; init; }

    public double? PulseEnergyUj { get; init; }

    /// <summary>Solves for the one missing quantity; throws <see cref="ProcessException"/> for bad, missing or contradictory values.</summary>
    public ProcessSolution Solve()
    {
        Positive(SpeedMmPerS, "speed", "mm/s");
        Positive(FrequencyHz, "frequency", "Hz");
        Positive(SpacingUm, "spacing", "µm");
        Positive(SpotDiameterUm, "spot diameter", "µm");
        Positive(PitchUm, "pitch", "µm");
        Positive(PulseEnergyUj, "pulse energy", "µJ");
        if (PulsesPerDot is < 1)
        {
            throw new ProcessException($"pulses per dot {PulsesPerDot} must be 1 or more");
        }

        if (SpacingUm is not null && OverlapPercent is not null)
        {
            throw new ProcessException("give the spacing or the overlap, not both (each fixes the other through the spot)");
        }

        var spacing = SpacingUm;
        if (OverlapPercent is { } overlap)
        {
            if (!double.IsFinite(overlap) || overlap >= 100)
            {
                throw new ProcessException($"overlap {N(overlap)} % must be below 100 % (100 % would be no spacing at all)");
            }

            spacing = PulseArithmetic.SpacingForOverlap(overlap / 100, SpotDiameterUm);
        }

        var missing = (SpeedMmPerS is null ? 1 : 0) + (FrequencyHz is null ? 1 : 0) + (spacing is null ? 1 : 0);
        if (missing > 1)
        {
            throw new ProcessException("give two of speed, frequency and spacing (or overlap); the third is solved from v = D f / N");
        }

        var warnings = new List<JobWarning>();
        var n = PulsesPerDot ?? 1;
        double v, f, d;
        ProcessQuantity solved;
        if (SpeedMmPerS is null)
        {
            (f, d, solved) = (FrequencyHz!.Value, spacing!.Value, ProcessQuantity.Speed);
            v = PulseArithmetic.SpeedMmPerS(d, f, n);
        }
        else if (FrequencyHz is null)
        {
            (v, d, solved) = (SpeedMmPerS.Value, spacing!.Value, ProcessQuantity.Frequency);
            f = PulseArithmetic.FrequencyHz(v, d, n);
            var whole = Math.Round(f, MidpointRounding.AwayFromZero);
            if (Math.Abs(f - whole) > Tolerance * f)
            {
                warnings.Add(new JobWarning(
                    JobWarningKind.FrequencyNotWhole,
                    $"the gate is sent whole Hz: {N(f)} Hz becomes {N(whole)} Hz, a spacing of {N(PulseArithmetic.SpacingUm(v, whole, n))} µm"));
            }
        }
        else if (spacing is null)
        {
            (v, f, solved) = (SpeedMmPerS.Value, FrequencyHz.Value, ProcessQuantity.Spacing);
            d = PulseArithmetic.SpacingUm(v, f, n);
        }
        else
        {
            (v, f, d) = (SpeedMmPerS.Value, FrequencyHz.Value, spacing.Value);
            var implied = PulseArithmetic.PulsesPerDot(v, f, d);
            if (PulsesPerDot is { } given)
            {
                if (Math.Abs(implied - given) > Tolerance * given)
                {
                    throw new ProcessException(
                        $"the values contradict each other: {N(d)} µm at {N(f)} Hz with {given} pulse(s) per dot needs {N(PulseArithmetic.SpeedMmPerS(d, f, given))} mm/s, not {N(v)} mm/s; leave one out to solve it");
                }

                solved = ProcessQuantity.None;
            }
            else
            {
                n = (int)Math.Round(implied, MidpointRounding.AwayFromZero);
                if (n < 1 || Math.Abs(implied - n) > 1e-6 * implied)
                {
                    throw new ProcessException(
                        $"{N(d)} µm at {N(f)} Hz and {N(v)} mm/s means {N(implied)} pulses per dot, not a whole number; change one value or leave one out to solve it");
                }

                solved = ProcessQuantity.PulsesPerDot;
            }
        }

        var figures = PulseFigures.For(v, f, SpotDiameterUm, PitchUm, PulseEnergyUj, n);
        return new ProcessSolution(solved, figures with { Warnings = [.. warnings, .. figures.Warnings] });
    }

    private static void Positive(double? value, string what, string unit)
    {
        if (value is { } v && !(v > 0 && double.IsFinite(v)))
        {
            throw new ProcessException($"{what} {N(v)} {unit} must be a finite number above 0");
        }
    }

    private static string N(double value) => value.ToString("0.######", CultureInfo.InvariantCulture);
}

/// <summary>What <see cref="ProcessQuery.Solve"/> found: which quantity it solved for and every figure.</summary>
public sealed record ProcessSolution(ProcessQuantity Solved, PulseFigures Figures);
