using LaserEngrave.Core.Planning;

namespace LaserEngrave.Devices.Execution;

/// <summary>
/// A stroke under way: its step and times, where the position queries found the stage against its plan, the gap being
/// flown, and the replies its first switch-on waits for.
/// </summary>
internal sealed class StrokeUnderWay(StrokeStep stroke, TimedSwitching timing, StrokeTimes times, StrokeCut.Stroke active)
{
    public StrokeStep Stroke { get; } = stroke;

    public TimedSwitching Timing { get; } = timing;

    public StrokeTimes Times { get; } = times;

    /// <summary>The stroke as the stop point's cut pixel reads it (its origin moved with <see cref="Shift"/>).</summary>
    public StrokeCut.Stroke Active { get; } = active;

    public Dictionary<long, StrokePlan.Bump> Bumps { get; } = stroke.Plan.Bumps.ToDictionary(b => b.Exit);

    /// <summary>
    /// Where the position queries after flown gaps found the stage ahead (-) or behind (+) its plan, as time at the burn
    /// speed; from the start, a move whose write completed late (a computer stalled before it) is that much behind.
    /// </summary>
    public double Shift { get; set; }

    public (StrokePlan.Bump Bump, StagePositionCheck.FlownQuery Query)? Flown { get; set; }

    public required ReplyWatch.Watched End { get; init; }

    public required double EndDeadline { get; init; }

    public required IReadOnlyList<ReplyWatch.Watched> Earlier { get; init; }

    public required StagePositionCheck.Answered<long>? Poll { get; init; }

    public required double MoveStamped { get; init; }

    public double PollLate { get; set; }

    /// <summary>When the switch-on of the run entering at <paramref name="x"/> is written, run seconds.</summary>
    public double OnWrite(long x) => Times.Arrival + Stroke.TimeAt(x) + Shift + Timing.OnDelaySeconds - Timing.OnLeadSeconds;

    /// <summary>When the switch-off of the run leaving at <paramref name="x"/> is written, run seconds.</summary>
    public double OffWrite(long x) => Times.Arrival + Stroke.TimeAt(x) + Shift - Timing.OffAdvanceSeconds - Timing.OffLeadSeconds;

    /// <summary>Whether the gap after the run leaving at <paramref name="x"/> is flown.</summary>
    public bool FlownAfter(long x) => Bumps.ContainsKey(Stroke.Distance(x));

    /// <summary>When the next run's scheduled switch-on is to be written (as <see cref="GateSwitching.ScheduledSwitchOnAsync"/> will compute it).</summary>
    public double NextScheduledWrite(Move next, double burstEndsAt)
    {
        var (nextOn, nextOff) = Effects(next);
        return Math.Min(Timing.ScheduledWriteSeconds(nextOn, nextOff, burstEndsAt), Timing.BurstWriteSeconds(nextOn, nextOff));
    }

    /// <summary>Whether the gap after a run carries the switch-off's line ahead of the next burst's (docs/execution.md, "The burst").</summary>
    public bool OffFitsBefore(Move next, double offEffect)
    {
        var (nextOn, nextOff) = Effects(next);
        return Timing.OffFitsBefore(offEffect, nextOn, Timing.PulsesWithin(nextOff - nextOn));
    }

    private (double On, double Off) Effects(Move next) =>
        (Times.Arrival + Stroke.TimeAt(next.X0) + Shift + Timing.OnDelaySeconds, Times.Arrival + Stroke.TimeAt(next.X1) + Shift - Timing.OffAdvanceSeconds);
}
