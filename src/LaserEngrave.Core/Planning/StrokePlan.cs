using System.Runtime.CompilerServices;
using LaserEngrave.Core.Motion;

namespace LaserEngrave.Core.Planning;

/// <summary>
/// One stroke of an optimized run under <see cref="TimedSwitching"/>: an X Move Absolute from rest to rest at the burn
/// speed, in which the gaps long enough are flown (<see cref="FlyingGap"/>): the target speed is raised to the travel
/// speed just after a run's exit edge and set back to the burn speed in time to be at it again, and measured, before the
/// next run's entry edge.
/// </summary>
/// <remarks>
/// Times are seconds from the stroke's start (its Move Absolute arriving), offsets microsteps from its start position.
/// Between and after the speed bumps the stage moves at the burn speed, so an edge is crossed as on the plain trapezoid,
/// earlier by what the bumps before it gained. The Zaber device replans a move whose target speed changes (docs/zaber-protocol.md):
/// it changes speed at its acceleration towards the new target speed and still stops at the move's target.
/// </remarks>
public sealed class StrokePlan
{
    private TrapezoidProfile _profile;
    private double _burnSpeed;

    // The flown gaps as values, so that the estimator can plan millions of strokes into one reused plan without
    // allocating; Bumps makes the records from them when a caller asks.
    private BumpTimes[] _bumps = [];
    private int _bumpCount;
    private IReadOnlyList<Bump>? _bumpRecords;

    internal StrokePlan(TimedSwitching timing, long length, IReadOnlyList<(long Exit, long Entry)> gaps)
    {
        var buffer = new (long Exit, long Entry)[gaps.Count];
        for (var i = 0; i < buffer.Length; i++)
        {
            buffer[i] = gaps[i];
        }

        Replan(timing, length, buffer);
    }

    /// <summary>An empty plan for <see cref="Replan"/> to fill.</summary>
    internal StrokePlan()
    {
    }

    /// <summary>Makes this the plan of another stroke (only for a plan its owner reuses, never one handed out).</summary>
    [MethodImpl(HotPath.Optimized)]
    internal void Replan(TimedSwitching timing, long length, ReadOnlySpan<(long Exit, long Entry)> gaps)
    {
        _profile = timing.Stroke(length);
        _burnSpeed = timing.BurnSpeed;
        Length = length;
        _bumpCount = 0;
        _bumpRecords = null;
        var gained = 0.0;
        foreach (var (exit, entry) in gaps)
        {
            if (timing.Flown(entry - exit) is not { } flown || !WithinDeviceRamp(timing, length, exit, flown))
            {
                continue;
            }

            var fly = flown.Fly;
            var exitTime = _profile.TimeAt(exit) - (gained / _burnSpeed);
            gained += fly.GainMicrosteps;
            var entryTime = _profile.TimeAt(entry) - (gained / _burnSpeed);
            var speedUp = exitTime + fly.SpeedUpDelaySeconds;
            var speedDown = speedUp + fly.HoldSeconds;
            var query = speedDown + fly.QueryDelaySeconds;
            if (_bumpCount == _bumps.Length)
            {
                Array.Resize(ref _bumps, Math.Max(8, _bumps.Length * 2));
            }

            _bumps[_bumpCount++] = new BumpTimes(exit, entry, speedUp, speedDown, query, entry - (_burnSpeed * (entryTime - query)), fly.MaxErrorMicrosteps, gained);
        }

        Gained = gained;
    }

    /// <summary>
    /// Whether the device, replanning its move to the stroke's end at the travel speed, is still speeding up or cruising
    /// when the speed-down arrives (near the end it would already brake towards the target, and the bump would not be
    /// the one planned).
    /// </summary>
    private static bool WithinDeviceRamp(TimedSwitching timing, long length, long exit, in FlownGap gap)
    {
        var a = timing.Acceleration;
        var burn = timing.BurnSpeed;
        var travel = timing.TravelSpeed;
        var remaining = length - (exit + gap.SpeedUpOffset);
        var peakSquared = (a * remaining) + (burn * burn / 2);

        // Far from the stroke's end the replanned move reaches the travel speed: no square root is needed to say so
        // (the margin keeps the rounded root at or above it), and the braking distance is the travel speed's.
        if (peakSquared >= travel * travel * (1 + 1e-12))
        {
            return gap.PeakSpeed <= travel + 1e-9 && gap.Covered <= remaining - (travel * travel / (2 * a));
        }

        var peak = Math.Min(travel, Math.Sqrt(peakSquared));
        return gap.PeakSpeed <= peak + 1e-9 && gap.Covered <= remaining - (peak * peak / (2 * a));
    }

    /// <summary>The stroke's length, microsteps.</summary>
    public long Length { get; private set; }

    /// <summary>The flown gaps, in stroke order.</summary>
    public IReadOnlyList<Bump> Bumps => _bumpRecords ??= BumpRecords();

    /// <summary>The flown gaps, in stroke order, as values.</summary>
    internal ReadOnlySpan<BumpTimes> BumpTimings => _bumps.AsSpan(0, _bumpCount);

    /// <summary>From the start to the end of the motion, s.</summary>
    public double Duration => _profile.Duration - (Gained / _burnSpeed);

    /// <summary>The highest speed the stroke brakes from at its end (the burn speed, or less for a short stroke), microsteps/s.</summary>
    public double PeakSpeed => _profile.PeakSpeed;

    private double Gained { get; set; }

    private Bump[] BumpRecords()
    {
        var records = new Bump[_bumpCount];
        for (var i = 0; i < records.Length; i++)
        {
            records[i] = _bumps[i].ToRecord();
        }

        return records;
    }

    /// <summary>When the stage crosses <paramref name="offset"/> (an edge, or any point outside the bumps), s from the start.</summary>
    public double TimeAt(long offset)
    {
        var gained = 0.0;
        foreach (ref readonly var bump in BumpTimings)
        {
            if (offset < bump.Entry)
            {
                break;
            }

            gained = bump.GainedUpTo;
        }

        return _profile.TimeAt(offset) - (gained / _burnSpeed);
    }

    /// <summary>
    /// Where the stage is <paramref name="seconds"/> after the start, microsteps from the start position, for a time
    /// outside the bumps (the inverse of <see cref="TimeAt"/>; within a bump, the burn-speed estimate before it).
    /// </summary>
    public double OffsetAt(double seconds)
    {
        if (seconds <= 0)
        {
            return 0;
        }

        long low = 0, high = Length;
        if (TimeAt(high) <= seconds)
        {
            return Length;
        }

        // TimeAt drops at each flown gap's entry edge by what the bump gained, so just after an entry the same time is also
        // reached inside the gap before it: search from the last entry crossed by then, where the times rise again. (A search
        // over the whole stroke could land in the gap and put the stage before a run it was already burning: issue 19, item 4.)
        foreach (ref readonly var bump in BumpTimings)
        {
            if (TimeAt(bump.Entry) > seconds)
            {
                break;
            }

            low = bump.Entry;
        }

        while (high - low > 1)
        {
            var mid = low + ((high - low) / 2);
            (low, high) = TimeAt(mid) <= seconds ? (mid, high) : (low, mid);
        }

        var t0 = TimeAt(low);
        var t1 = TimeAt(high);
        return t1 > t0 ? low + ((seconds - t0) / (t1 - t0)) : low;
    }

    /// <summary>One flown gap: when its commands arrive at the stage and where the position query must find it.</summary>
    /// <param name="Exit">The exit edge before the gap, microsteps from the start.</param>
    /// <param name="Entry">The entry edge after the gap.</param>
    /// <param name="SpeedUpArrival">When Set Target Speed (travel) arrives, s from the start.</param>
    /// <param name="SpeedDownArrival">When Set Target Speed (burn) arrives.</param>
    /// <param name="QueryArrival">When the position query arrives: the stage is back at the burn speed.</param>
    /// <param name="ExpectedOffset">Where the query should find the stage, microsteps from the start.</param>
    /// <param name="MaxErrorMicrosteps">How far from <paramref name="ExpectedOffset"/> the latencies can put it.</param>
    /// <param name="GainedUpTo">What this bump and those before it gained on the burn speed, microsteps.</param>
    public sealed record Bump(long Exit, long Entry, double SpeedUpArrival, double SpeedDownArrival, double QueryArrival, double ExpectedOffset, double MaxErrorMicrosteps, double GainedUpTo);

    /// <summary>A <see cref="Bump"/> as a value.</summary>
    internal readonly record struct BumpTimes(long Exit, long Entry, double SpeedUpArrival, double SpeedDownArrival, double QueryArrival, double ExpectedOffset, double MaxErrorMicrosteps, double GainedUpTo)
    {
        public Bump ToRecord() => new(Exit, Entry, SpeedUpArrival, SpeedDownArrival, QueryArrival, ExpectedOffset, MaxErrorMicrosteps, GainedUpTo);
    }
}

/// <summary>How a gap is flown: the speed bump's timing and what it gains (see <see cref="TimedSwitching.Fly"/>).</summary>
/// <param name="SpeedUpDelaySeconds">From crossing the exit edge to the speed-up arriving.</param>
/// <param name="HoldSeconds">From the speed-up arriving to the speed-down arriving.</param>
/// <param name="QueryDelaySeconds">From the speed-down arriving to the position query arriving.</param>
/// <param name="GainMicrosteps">Distance gained on the burn speed: the gap is crossed this much sooner, divided by the burn speed.</param>
/// <param name="MaxErrorMicrosteps">The most the latencies can move the stage from its nominal position after the bump.</param>
public readonly record struct FlyingGap(double SpeedUpDelaySeconds, double HoldSeconds, double QueryDelaySeconds, double GainMicrosteps, double MaxErrorMicrosteps);

/// <summary>
/// A gap that can be flown, with what the check against the device's own ramp needs of it (<see cref="StrokePlan"/>),
/// worked out once per gap length: where the speed-up starts after the exit edge, the speed it rises to, and the
/// distance covered until the speed-down arrives.
/// </summary>
internal readonly record struct FlownGap(FlyingGap Fly, double SpeedUpOffset, double PeakSpeed, double Covered)
{
    public static FlownGap Of(TimedSwitching timing, FlyingGap fly)
    {
        var a = timing.Acceleration;
        var burn = timing.BurnSpeed;
        var rise = Math.Min(a * fly.HoldSeconds, timing.TravelSpeed - burn);
        var ramp = rise / a;
        var covered = (burn * fly.HoldSeconds) + (0.5 * rise * ramp) + (rise * (fly.HoldSeconds - ramp));
        return new FlownGap(fly, burn * fly.SpeedUpDelaySeconds, burn + rise, covered);
    }
}
