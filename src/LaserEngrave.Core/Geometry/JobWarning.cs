namespace LaserEngrave.Core.Geometry;

/// <summary>What a job warning is about.</summary>
public enum JobWarningKind
{
    /// <summary>The pixel pitch is below one microstep: neighbouring edges can fall on the same microstep.</summary>
    PitchBelowMicrostep,

    /// <summary>Part of the job lies outside the stage's travel.</summary>
    OutsideTravel,

    /// <summary>The pixel pitch is smaller than the laser spot: each pixel burns wider than it is.</summary>
    PitchBelowSpot,

    /// <summary>The overscan run-up or run-out reaches past the stage's travel and is shortened there.</summary>
    OverscanClamped,

    /// <summary>The pulse spacing is above the spot diameter: the pulses leave gaps along a line.</summary>
    PulseGaps,

    /// <summary>A pixel gets less than one pulse on average: some pixels get none.</summary>
    PixelUnderOnePulse,

    /// <summary>A solved laser frequency is not whole Hz; the gate is sent the nearest whole number.</summary>
    FrequencyNotWhole,

    /// <summary>A pixel lasts less at the burn speed than the gate needs to switch it: the plan can be looked at, not engraved.</summary>
    PixelTooShortForTheGate,

    /// <summary>A dot's burst lasts too long for the gate's watchdog: the plan can be looked at, not engraved.</summary>
    BurstTooLongForTheWatchdog,
}

/// <summary>A condition the job can run with but the user should know about.</summary>
/// <param name="Kind">What the warning is about, for code that reacts to it.</param>
/// <param name="Message">One line for the user, with the numbers.</param>
public sealed record JobWarning(JobWarningKind Kind, string Message);
