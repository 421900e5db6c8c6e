namespace LaserEngrave.Core.Planning;

/// <summary>Totals of a plan and its estimated duration, computed by streaming its moves once.</summary>
public sealed record PlanStatistics
{
    /// <summary>Image rows that have moves (all rows under <see cref="PlanStrategy.Paper"/>, non-blank rows otherwise).</summary>
    public required int Rows { get; init; }

    public required long Moves { get; init; }

    /// <summary>Burn moves (laser on).</summary>
    public required long BurnRuns { get; init; }

    /// <summary>Distance travelled with the laser on, mm.</summary>
    public required double BurnLengthMm { get; init; }

    /// <summary>Distance travelled with the laser off (travels and overscans; a diagonal travel counts its straight length), mm.</summary>
    public required double TravelLengthMm { get; init; }

    /// <summary>The part of <see cref="TravelLengthMm"/> run as overscan at the burn speed, mm.</summary>
    public required double OverscanLengthMm { get; init; }

    /// <summary>Laser gate commands sent: each switch on, each switch off, the final switch-off included.</summary>
    public required long LaserSwitches { get; init; }

    /// <summary>Set Target Speed commands sent after the start.</summary>
    public required long SpeedChanges { get; init; }

    /// <summary>Estimated duration of the engraving, from the plan's first move to its last, s (see <see cref="PlanEstimator"/> for the model).</summary>
    public required double EngravingSeconds { get; init; }

    /// <summary>
    /// Estimated time before the engraving of the first pass: preflight, homing from the far end of the travel (as after
    /// power-up; a stage already homed is sooner) and the travel to the first position (<see cref="TimedSwitching.PreparationSeconds"/>);
    /// 0 for a plan without a timing model.
    /// </summary>
    public double PreparationSeconds { get; init; }

    /// <summary>Estimated time before each later pass: preflight without homing and the travel back from the plan's end to its start, s.</summary>
    public double PassSetupSeconds { get; init; }

    /// <summary>Where the plan starts and ends, microsteps (null for a plan without moves): a later layer of a job travels from one's end to the next one's start.</summary>
    public ((long X, long Y) First, (long X, long Y) Last)? Ends { get; init; }

    /// <summary>The estimate of a whole run of <paramref name="passes"/> passes: preparation, engraving, and each later pass' setup, s.</summary>
    public double WholeRunSeconds(int passes = 1) =>
        PreparationSeconds + (Math.Max(1, passes) * EngravingSeconds) + (Math.Max(0, passes - 1) * PassSetupSeconds);

    /// <summary>The least time any executor could take for the burns, motion only, s (see <see cref="LowerBound"/>).</summary>
    public required double LowerBoundSeconds { get; init; }
}
