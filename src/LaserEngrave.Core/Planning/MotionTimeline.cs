using System.Runtime.CompilerServices;

namespace LaserEngrave.Core.Planning;

/// <summary>
/// The nominal times of an optimized run's motions under <see cref="TimedSwitching"/>, one after the other: when each
/// command arrives at the stage and when each motion ends. The executor sends its commands by it and
/// <see cref="PlanEstimator"/> adds up its times, so both follow one schedule.
/// </summary>
/// <remarks>
/// <list type="bullet">
/// <item>A move arrives a margin after the axis' previous motion ended (never pre-empting it).</item>
/// <item>A change of X speed is sent just ahead of the move that needs it, so it arrives while the motion before brakes
/// (at or below the new speed, so the braking does not change); when that window is too short it arrives after the
/// motion ended and the move follows one frame later.</item>
/// <item>A Y move in a row change arrives as soon as the last burn run's switch-off has taken effect, while X still brakes;
/// the next stroke's first edge comes a margin after Y has stopped.</item>
/// </list>
/// Times are seconds on the run's clock (0 = the start settings sent).
/// </remarks>
public sealed class MotionTimeline
{
    private readonly TimedSwitching _timing;

    // When each reply still to come leaves its device, in order: replies share the wire back to the host, one frame
    // each. Kept sorted as they are added, which is nearly always at the end.
    private List<double> _replies = [];

    public MotionTimeline(TimedSwitching timing, double startSeconds, int xSpeedData)
    {
        ArgumentNullException.ThrowIfNull(timing);
        _timing = timing;
        XFree = startSeconds;
        YFree = startSeconds;

        // Nothing written from now can arrive before a command's latency has passed.
        WireFree = startSeconds + timing.StageCommandSeconds - timing.FrameSeconds;
        XSpeedData = xSpeedData;
    }

    /// <summary>A timeline that goes on from where this one is, independently.</summary>
    public MotionTimeline Clone()
    {
        // Member by member, so that a field added later is copied too; the replies still to come are the one list.
        var copy = (MotionTimeline)MemberwiseClone();
        copy._replies = [.. _replies];
        return copy;
    }

    /// <summary>When the X axis has stopped after its last motion.</summary>
    public double XFree { get; private set; }

    /// <summary>When the Y axis has stopped after its last motion.</summary>
    public double YFree { get; private set; }

    /// <summary>When the last command sent has finished arriving (the stage's wire is free).</summary>
    public double WireFree { get; private set; }

    /// <summary>The X axis' target speed data after the commands so far.</summary>
    public int XSpeedData { get; private set; }

    /// <summary>The nominal time of the last switch-off (null before the first stroke, and after a travel).</summary>
    public double? LastOff { get; private set; }

    /// <summary>When everything has stopped.</summary>
    public double End => Math.Max(XFree, YFree);

    private double LastXPeak { get; set; }

    /// <summary>A travel with the laser off; returns when its commands arrive and when it ends.</summary>
    public TravelTimes Travel(long dx, long dy)
    {
        var t = _timing;
        double? speedArrival = null;
        double? xArrival = null;
        double? yArrival = null;
        if (dy != 0)
        {
            var y = Math.Max(YFree + t.MarginSeconds, WireFree + t.FrameSeconds);
            if (LastOff is { } off)
            {
                y = Math.Max(y, off + t.AfterOffSeconds);
            }

            yArrival = y;
            WireFree = y;
            YFree = y + t.Travel(dy).Duration;
        }

        if (dx != 0)
        {
            (speedArrival, xArrival) = MoveX(t.TravelSpeedData, t.TravelSpeed, LastOff is { } lastOff ? lastOff + t.AfterOffSeconds : double.NegativeInfinity);
            var travel = t.Travel(dx);
            XFree = xArrival.Value + travel.Duration;
            LastXPeak = travel.PeakSpeed;
        }

        LastOff = null;
        AddReply(speedArrival);
        AddReply(xArrival is null ? null : XFree);
        AddReply(yArrival is null ? null : YFree);
        return new TravelTimes(speedArrival, xArrival, yArrival, XFree, YFree);
    }

    /// <summary>
    /// A stroke: one X move from rest to rest at the burn speed (its flown gaps sped up), whose first entry edge comes
    /// <paramref name="firstEdgeSeconds"/> after it starts and whose last exit edge <paramref name="lastOffSeconds"/>
    /// after; returns when its commands arrive.
    /// </summary>
    [MethodImpl(HotPath.Optimized)]
    public StrokeTimes Stroke(StrokePlan stroke, double firstEdgeSeconds, double lastOffSeconds)
    {
        ArgumentNullException.ThrowIfNull(stroke);
        var t = _timing;

        // Y must have stopped, and said so, before the first switch-on is sent; its reply leaves before the position
        // query's, which the switch-on waits for.
        var notBefore = Math.Max(YFree, YFree + t.AfterYSeconds + t.OnLeadSeconds - (firstEdgeSeconds + t.OnDelaySeconds));
        var (speedArrival, arrival) = MoveX(t.BurnSpeedData, t.BurnSpeed, notBefore);
        AddReply(speedArrival);

        // The position query's reply leaves one frame after the move arrives: not behind another reply, which would
        // hold up the switch-on waiting for it.
        for (var i = 0; i < 8; i++)
        {
            var query = arrival + t.FrameSeconds;
            var clear = ReplyWireClear(query) + (2 * t.StageJitterSeconds);
            if (clear <= query)
            {
                break;
            }

            arrival += clear - query;
        }

        WireFree = Math.Max(WireFree, arrival + t.FrameSeconds);
        AddReply(arrival + t.FrameSeconds);

        // A flown gap's two speed changes and its position query, each answered as it arrives.
        foreach (ref readonly var bump in stroke.BumpTimings)
        {
            AddReply(arrival + bump.SpeedUpArrival);
            AddReply(arrival + bump.SpeedDownArrival);
            AddReply(arrival + bump.QueryArrival);
            WireFree = Math.Max(WireFree, arrival + bump.QueryArrival);
        }

        XFree = arrival + stroke.Duration;
        LastXPeak = stroke.PeakSpeed;
        LastOff = arrival + lastOffSeconds - t.OffAdvanceSeconds;
        AddReply(XFree);
        return new StrokeTimes(speedArrival, arrival, XFree);
    }

    /// <summary>The last stroke (or, with <paramref name="travel"/>, travel) started <paramref name="seconds"/> later than planned (its commands left late): it ends that much later.</summary>
    public void Delay(double seconds, bool travel = false)
    {
        XFree += seconds;
        WireFree += seconds;
        if (travel)
        {
            YFree += seconds;
        }

        if (LastOff is { } off)
        {
            LastOff = off + seconds;
        }
    }

    private void AddReply(double? readyAt)
    {
        if (readyAt is { } ready)
        {
            InsertSorted(_replies, ready);
        }
    }

    /// <summary>Inserts <paramref name="value"/> into the sorted <paramref name="list"/> where <see cref="List{T}.Sort()"/> would put it (NaN first).</summary>
    [MethodImpl(HotPath.Optimized)]
    internal static void InsertSorted(List<double> list, double value)
    {
        var count = list.Count;
        if (count == 0 || list[count - 1] <= value)
        {
            list.Add(value);
            return;
        }

        var i = double.IsNaN(value) ? 0 : count;
        while (i > 0 && list[i - 1] > value)
        {
            i--;
        }

        list.Insert(i, value);
    }

    // When the wire back is free of every reply that is ready before `at` (they leave in the order they are ready).
    [MethodImpl(HotPath.Optimized)]
    private double ReplyWireClear(double at)
    {
        var free = double.NegativeInfinity;
        var keepFrom = 0;
        for (var i = 0; i < _replies.Count && _replies[i] < at; i++)
        {
            free = Math.Max(free, _replies[i]) + _timing.FrameSeconds;
            if (free < at - 1)
            {
                keepFrom = i + 1;
            }
        }

        // Replies long gone no longer matter.
        _replies.RemoveRange(0, keepFrom);
        return free;
    }

    private (double? SpeedArrival, double Arrival) MoveX(int speedData, double speed, double notBefore = double.NegativeInfinity)
    {
        var t = _timing;
        var free = Math.Max(XFree + t.MarginSeconds, WireFree + t.FrameSeconds);
        var arrival = Math.Max(free, notBefore);
        double? speedArrival = null;
        if (XSpeedData != speedData)
        {
            XSpeedData = speedData;

            // Ahead of the move, while the motion before brakes: after its last switch-off, never before the wire is free.
            var earliest = Math.Max(WireFree + t.FrameSeconds, (LastOff ?? double.NegativeInfinity) + t.StageCommandSeconds);
            if (t.CanSetSpeedWhileBraking(LastXPeak, speed) && arrival - t.FrameSeconds - t.MarginSeconds >= earliest)
            {
                speedArrival = arrival - t.FrameSeconds - t.MarginSeconds;
            }
            else
            {
                speedArrival = Math.Max(free, earliest);
                arrival = Math.Max(arrival, speedArrival.Value + t.FrameSeconds);
            }
        }

        WireFree = arrival;
        return (speedArrival, arrival);
    }
}

/// <summary>When a travel's commands arrive (null: not sent) and when each axis stops.</summary>
public readonly record struct TravelTimes(double? SpeedArrival, double? XArrival, double? YArrival, double XEnd, double YEnd);

/// <summary>When a stroke's speed change (null: none) and move arrive, and when it ends.</summary>
public readonly record struct StrokeTimes(double? SpeedArrival, double Arrival, double End);
