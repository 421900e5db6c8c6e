using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Planning;

/// <summary>What a dot-mode plan (<see cref="PlanMode.Dots"/>) costs: its dots and rows, and the time the executor takes, part by part.</summary>
/// <remarks>
/// It adds up the steps of the plan's <see cref="DotProgram"/>, the ones the executor sends, by the model of <see cref="DotTiming"/>: the start settings, then for each dot
/// after the first the step from the dot before (travel speed, commands and replies), and at every dot the settle time, the
/// burst command, its acknowledgement and the wait for the burst's end; at the end the switch-off. The travel to the first
/// dot is not part of the engraving (as in raster mode).
/// </remarks>
public sealed record DotModeEstimate
{
    public required long Dots { get; init; }

    /// <summary>Rows with at least one dot.</summary>
    public required int Rows { get; init; }

    public required int PulsesPerDot { get; init; }

    /// <summary>Time the laser fires at one dot: N / f, seconds.</summary>
    public required double BurstSeconds { get; init; }

    public required double SettleSeconds { get; init; }

    /// <summary>At one dot: settle, burst command and acknowledgement, and the wait for the burst's end, seconds.</summary>
    public required double AtDotSeconds { get; init; }

    /// <summary>All steps from dot to dot (motion, commands and replies), seconds.</summary>
    public required double StepsSeconds { get; init; }

    /// <summary>The start settings and the final switch-off, seconds.</summary>
    public required double StartEndSeconds { get; init; }

    /// <summary>The stage's travel between dots, mm (the laser is off throughout).</summary>
    public required double TravelLengthMm { get; init; }

    /// <summary>Dwell at a dot: burst plus settle, seconds.</summary>
    public double DwellSeconds => BurstSeconds + SettleSeconds;

    /// <summary>The whole engraving, seconds.</summary>
    public double TotalSeconds => StartEndSeconds + StepsSeconds + (Dots * AtDotSeconds);

    /// <summary>Pulses the plan fires in all.</summary>
    public long Pulses => Dots * PulsesPerDot;

    /// <summary>Adds up the steps of <paramref name="program"/> in one pass, as the executor runs them.</summary>
    public static DotModeEstimate For(DotProgram program)
    {
        ArgumentNullException.ThrowIfNull(program);
        var timing = program.Timing;
        long dots = 0;
        var rows = 0;
        var lastRow = -1;
        double steps = 0, travel = 0;
        DotStep previous = default;
        foreach (var dot in program.Steps())
        {
            if (dots > 0)
            {
                steps += program.MoveSeconds(previous, dot);
                travel += Math.Sqrt(Square(dot.X - previous.X) + Square(dot.Y - previous.Y));
            }

            rows += dot.Row != lastRow ? 1 : 0;
            lastRow = dot.Row;
            previous = dot;
            dots++;
        }

        return new DotModeEstimate
        {
            Dots = dots,
            Rows = rows,
            PulsesPerDot = timing.PulsesPerDot,
            BurstSeconds = timing.BurstSeconds,
            SettleSeconds = timing.SettleSeconds,
            AtDotSeconds = timing.AtDotSeconds,
            StepsSeconds = steps,
            StartEndSeconds = timing.StartSeconds + timing.OffRoundTripSeconds,
            TravelLengthMm = StageUnits.MicrostepsToMm(travel, program.MicrostepUm),
        };

        static double Square(double v) => v * v;
    }
}
