namespace LaserEngrave.Core.Planning;

/// <summary>Where a run that did not complete stopped: the first move not completed and the stage's last known position.</summary>
/// <param name="Row">The image row of the first move not completed (0 = top row), or an earlier one.</param>
/// <param name="MoveIndex">Its index in the plan's moves (<see cref="Planning.RasterPlan.Moves()"/>); a resumed run starts here.</param>
/// <param name="XMicrosteps">Stage X when it stopped, microsteps; null when unknown.</param>
/// <param name="YMicrosteps">Stage Y when it stopped, microsteps; null when unknown.</param>
public sealed record RunStopPoint(int Row, long MoveIndex, long? XMicrosteps = null, long? YMicrosteps = null)
{
    /// <summary>
    /// When the run stopped in the middle of a burn run (the move at <see cref="MoveIndex"/>): the X, microsteps, of the
    /// first pixel edge not completely burned, found from the time the laser went off and the stroke's motion. A resumed
    /// run burns the run from here, so only the pixel the fault cut through (<see cref="CutPixel"/>) is burned twice.
    /// Null: the run resumes at the move's start.
    /// </summary>
    public long? ResumeXMicrosteps { get; init; }

    /// <summary>The pixel (column, row of the image) the laser went off in, burned again on resuming; null with no <see cref="ResumeXMicrosteps"/>.</summary>
    public PixelIndex? CutPixel { get; init; }

    /// <summary>
    /// Where the X axis must be found on resuming for <see cref="ResumeXMicrosteps"/> to hold (the stroke's end): set
    /// when the stage could not be asked after the fault; null when its position was already checked against its motion.
    /// </summary>
    public long? ExpectedXMicrosteps { get; init; }

    /// <summary>
    /// The gate's link was lost with the laser on: the gate went on firing until its own watchdog tripped, a watchdog
    /// time after the last command it had, and <see cref="ResumeXMicrosteps"/> counts on that. On resuming the gate must
    /// report its watchdog tripped (else the run is burned again from its start).
    /// </summary>
    public bool OffByGateWatchdog { get; init; }

    /// <summary>
    /// With <see cref="OffByGateWatchdog"/>: where the run resumes when the gate reports its watchdog did not trip, so that a
    /// command it heard switched the laser off (the fault's first OFF at the earliest: a gate that carried it out without
    /// acknowledging it); null: the run is then burned again from the move's start.
    /// </summary>
    public long? OffResumeXMicrosteps { get; init; }

    /// <summary>The pixel the laser went off in when the gate's watchdog did not trip (<see cref="OffResumeXMicrosteps"/>), burned again on resuming.</summary>
    public PixelIndex? OffCutPixel { get; init; }
}

/// <summary>A pixel of the job's image.</summary>
public readonly record struct PixelIndex(int Column, int Row);
