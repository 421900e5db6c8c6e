using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Devices.Execution;

/// <summary>
/// Where a timed run was when a fault or an abort cut it, and the cut pixel of its stop point: the stroke under way, the
/// burn run whose switch-on was sent and whose switch-off not yet, when the fault's switch-off left, when the gate last
/// showed it was alive, and whether the X axis stopped where the stroke's motion said.
/// </summary>
/// <remarks>Not locked itself: the engine calls it under its own lock.</remarks>
internal sealed class StrokeCut
{
    private Stroke? _stroke;
    private Travel? _travel;
    private (Move Move, long Index, Task Acknowledged, double BurstEndsAt)? _burning;
    private double? _faultOffWrite;
    private bool? _stopMatchesMotion;
    private double _gateAliveAt = double.NegativeInfinity;

    /// <summary>The acknowledgement of the burning run's switch-on, while a run is burning.</summary>
    public Task? SwitchOnAcknowledged => _burning?.Acknowledged;

    /// <summary>A stroke starts: from here a stop is cut along its motion.</summary>
    public void Started(Stroke stroke)
    {
        _stroke = stroke;
        _travel = null;
    }

    /// <summary>A travel's commands leave: <paramref name="move"/> (the plan's <paramref name="index"/>-th), each axis's move arriving then (s on the run's clock; null: that axis stays).</summary>
    public void Travelling(Move move, long index, double? xArrival, double? yArrival) => _travel = new(move, index, xArrival, yArrival);

    /// <summary>A burn run's switch-on was sent (<paramref name="acknowledged"/> its reply; its burst stops by itself by <paramref name="burstEndsAt"/> at the latest, s on the run's clock).</summary>
    public void Burning(Move burn, long index, Task acknowledged, double burstEndsAt = double.PositiveInfinity) => _burning = (burn, index, acknowledged, burstEndsAt);

    /// <summary>The burn run's laser is off again (its switch-off sent, or its burst ended by itself).</summary>
    public void NotBurning() => _burning = null;

    /// <summary>A flown gap's speed-up has been sent: from here the stroke's plan holds that gap.</summary>
    public void GapFlown()
    {
        if (_stroke is { } stroke)
        {
            stroke.GapsFlown++;
        }
    }

    /// <summary>The fault's switch-off left at <paramref name="seconds"/>: a burn run cut by it is burned up to there.</summary>
    public void FaultOffSent(double seconds) => _faultOffWrite ??= seconds;

    /// <summary>The gate answered: its reply left it at <paramref name="seconds"/> (s on the run's clock).</summary>
    public void GateAlive(double seconds) => _gateAliveAt = Math.Max(_gateAliveAt, seconds);

    /// <summary>The X axis' reply to the stop after a fault: whether it stopped where the stroke's motion put it (braking from the burn speed).</summary>
    /// <param name="written">When the stop was written, s on the run's clock (NaN before the engraving started).</param>
    public void Stopped(double written, long position, TimedSwitching timing)
    {
        if (_stroke is not { } stroke || double.IsNaN(written))
        {
            return;
        }

        var arrival = written + timing.StageCommandSeconds - stroke.Origin;
        var along = Along(stroke, arrival, timing);
        var expected = along >= stroke.Plan.Length
            ? stroke.EndX
            : stroke.StartX + (stroke.Direction * (along + (timing.BurnSpeed * timing.BurnSpeed / (2 * timing.Acceleration))));
        var tolerance = (2 * timing.BurnSpeed * timing.StageJitterSeconds) + 2;
        _stopMatchesMotion ??= Math.Abs(position - expected) <= tolerance;
    }

    /// <summary>
    /// The stop point of a timed run cut off in the middle of a burn run (issue: resume without double burn): the time
    /// the fault's switch-off took effect, at the earliest, and the stroke's motion say how far the run was burned;
    /// the run resumes at the first pixel not completely burned, so only the one the laser went off in burns twice.
    /// The motion is trusted only if the X axis stopped where it said, or, when it could not be asked, is found at the
    /// stroke's end on resuming (<see cref="RunStopPoint.ExpectedXMicrosteps"/>).
    /// </summary>
    /// <param name="offConfirmed">Whether the gate confirmed the laser off.</param>
    /// <param name="watchdogMs">The gate's watchdog time, after which a gate out of reach switched the laser off by itself (0: no watchdog, so such a gate's laser went off at no known time).</param>
    /// <param name="stoppedX">Where X stopped, when it said.</param>
    /// <param name="switchOnRefused">Whether the gate refused a switch-on (an error reply): the laser did not come on for that run.</param>
    public RunStopPoint Cut(RunStopPoint stop, TimedSwitching timing, RasterPlan plan, bool offConfirmed, int watchdogMs, long? stoppedX, Func<Task, bool> switchOnRefused)
    {
        if (_burning is not { } burning || burning.Index != stop.MoveIndex
            || _stroke is not { } stroke || _stopMatchesMotion == false || switchOnRefused(burning.Acknowledged))
        {
            return stop;
        }

        // A switch-on never acknowledged (its reply lost, garbled or too late) may still have fired: the gate carries
        // out what it hears. The laser then burned from the run's start to where it went off, and the resumed run burns it again.
        var fired = burning.Acknowledged.IsCompletedSuccessfully;

        // Off when the gate confirmed the fault's switch-off (its lead after it left, at the earliest). With the gate's
        // link lost, it fired on until its watchdog tripped, a watchdog time after the last command it had: at the
        // earliest after the last one it answered (the resumed run checks that the watchdog did trip).
        double offAt;
        var byWatchdog = false;
        if (offConfirmed && _faultOffWrite is { } offWrite)
        {
            offAt = offWrite + timing.OffLeadSeconds - timing.GateJitterSeconds;
        }
        else if (!offConfirmed && ((watchdogMs > 0 && _gateAliveAt > double.NegativeInfinity) || (!fired && _faultOffWrite is not null && double.IsFinite(burning.BurstEndsAt))))
        {
            // Never later than the burst's own end: a gate that heard its switch-on counts its pulses whatever it hears
            // next. A gate that answered nothing in this run (its first switch-on never acknowledged, a resumed run's
            // too) is bounded by that alone; the first OFF's cut below then names the pixel a gate that heard it went off in.
            // A gate without a watchdog (frequency-only) never switches itself off: only its burst's end bounds it, and
            // such a gate has none (infinite), so it reaches here only with a watchdog.
            var watchdogOff = watchdogMs > 0 && _gateAliveAt > double.NegativeInfinity ? _gateAliveAt + Units.MsToSeconds(watchdogMs) - timing.GateJitterSeconds : double.PositiveInfinity;
            offAt = Math.Min(watchdogOff, burning.BurstEndsAt - (2 * timing.GateJitterSeconds));
            byWatchdog = true;
        }
        else
        {
            return stop;
        }

        var (resumeX, cutPixel) = CutAt(offAt, burning.Move, stroke, timing, fired, plan, stoppedX);
        if (cutPixel is null)
        {
            return stop;
        }

        // Counting on the watchdog, which a gate that heard the fault's OFF (and carried it out unacknowledged) never
        // trips: the resumed run then takes the cut at that OFF, the earliest the laser can have gone off.
        var (offResumeX, offCut) = byWatchdog && _faultOffWrite is { } firstOff
            ? CutAt(firstOff + timing.OffLeadSeconds - timing.GateJitterSeconds, burning.Move, stroke, timing, fired, plan, stoppedX)
            : (null, null);
        return stop with
        {
            ResumeXMicrosteps = resumeX,
            CutPixel = cutPixel,
            ExpectedXMicrosteps = resumeX is not null && _stopMatchesMotion is null ? stroke.EndX : null,
            OffByGateWatchdog = byWatchdog,
            OffResumeXMicrosteps = offResumeX,
            OffCutPixel = offCut,
        };
    }

    /// <summary>
    /// The cut of a burn run whose laser went off at <paramref name="offAt"/> (s on the run's clock): the first pixel edge
    /// not completely burned and the pixel the laser went off in; no edge when the run burns again from its start (off
    /// inside its first pixel, or a switch-on not known to have fired), no pixel when it went off before the run.
    /// </summary>
    private static (long? ResumeX, PixelIndex? Cut) CutAt(double offAt, Move burn, Stroke stroke, TimedSwitching timing, bool fired, RasterPlan plan, long? stoppedX)
    {
        var along = Along(stroke, offAt - stroke.Origin, timing) - (timing.BurnSpeed * timing.StageJitterSeconds);
        if (stoppedX is { } x)
        {
            // Stopped while the laser still fired (its gate out of reach): it burned no further than where X stopped.
            along = Math.Min(along, (x - stroke.StartX) * stroke.Direction);
        }

        var burnedTo = stroke.StartX + (stroke.Direction * along);
        if (fired && plan.ResumeWithin(burn, burnedTo) is { } cut)
        {
            return (cut.ResumeX, new PixelIndex(cut.Column, burn.Row));
        }

        // Off within the run's first pixel, or a switch-on not known to have fired: the run burns again from its
        // start, so the pixel the laser went off in is the one that may get part of its dose twice; the log names it.
        if ((burnedTo - burn.X0) * stroke.Direction < 0)
        {
            return (null, null);
        }

        var column = plan.ColumnAt(burn, Math.Clamp(burnedTo, Math.Min(burn.X0, burn.X1), Math.Max(burn.X0, burn.X1)));
        return (null, new PixelIndex(column, burn.Row));
    }

    /// <summary>
    /// Where the stroke's motion put X <paramref name="seconds"/> after its origin, microsteps from its start: its plan,
    /// but at the burn speed on from a flown gap whose speed-up was never sent (the run ended first), as the stage went.
    /// </summary>
    private static double Along(Stroke stroke, double seconds, TimedSwitching timing)
    {
        var unflown = stroke.Plan.Bumps.OrderBy(b => b.Exit).Skip(stroke.GapsFlown).FirstOrDefault();
        return unflown is not null && seconds > unflown.SpeedUpArrival
            ? Math.Min(stroke.Plan.Length, stroke.Plan.OffsetAt(unflown.SpeedUpArrival) + (timing.BurnSpeed * (seconds - unflown.SpeedUpArrival)))
            : stroke.Plan.OffsetAt(seconds);
    }

    /// <summary>
    /// Where the stroke's motion puts the stage at <paramref name="seconds"/> on the run's clock, with the flown gaps'
    /// speed bumps as the stage goes through them (the device's ramps to the travel speed and back); null before its
    /// move arrives or without a stroke.
    /// </summary>
    public StrokePosition? PositionAt(double seconds, TimedSwitching timing)
    {
        // X where the stroke put it (at rest at its start before its move arrives, at its end after it).
        long? strokeX = _stroke is { } stroke
            ? (long)Math.Round(stroke.StartX + (stroke.Direction * (seconds < stroke.Origin ? 0 : Flying(stroke, seconds - stroke.Origin, timing))))
            : null;
        if (_travel is { } travel)
        {
            // A travel after the stroke: each axis from its move's arrival along the travel's ramps; until then where it was.
            var move = travel.Move;
            long Axis(long from, long to, double? arrival) => arrival is { } at && seconds >= at
                ? from + (Math.Sign(to - from) * (long)Math.Round(timing.Travel(Math.Abs(to - from)).DistanceAt(seconds - at)))
                : from;
            var x = travel.XArrival is { } xa && seconds >= xa ? Axis(move.X0, move.X1, xa) : strokeX ?? move.X0;
            return new StrokePosition(x, Axis(move.Y0, move.Y1, travel.YArrival), travel.Index, 1);
        }

        return _stroke is { } s ? new StrokePosition(strokeX!.Value, s.Y, s.FirstMoveIndex, s.MoveCount) : null;
    }

    /// <summary>A travel of a timed run: its move and when each axis's move arrives (s on the run's clock).</summary>
    private sealed record Travel(Move Move, long Index, double? XArrival, double? YArrival);

    /// <summary>
    /// <see cref="Along"/>, and inside a flown gap the bump itself: from its speed-up's arrival the device speeds up at its
    /// acceleration towards the travel speed, and from its speed-down's it slows back to the burn speed (TimedSwitching.Fly).
    /// </summary>
    private static double Flying(Stroke stroke, double seconds, TimedSwitching timing)
    {
        var a = timing.Acceleration;
        var flown = 0;
        foreach (var bump in stroke.Plan.Bumps)
        {
            if (seconds <= bump.SpeedUpArrival || flown++ >= stroke.GapsFlown)
            {
                break;
            }

            // The plan's own times hold again from the entry edge on; before it, the stage is past the bump's burn-speed estimate.
            var hold = bump.SpeedDownArrival - bump.SpeedUpArrival;
            var rise = Math.Min(a * hold, timing.TravelSpeed - timing.BurnSpeed);
            if (rise <= 0 || seconds >= stroke.Plan.TimeAt(bump.Entry))
            {
                continue;
            }

            var t = seconds - bump.SpeedUpArrival;
            double Gain(double s) => a * s < rise ? a * s * s / 2 : (rise * rise / (2 * a)) + (rise * (s - (rise / a)));
            var down = Math.Min(t - hold, rise / a);
            var gained = t <= hold ? Gain(t) : Gain(hold) + (rise * down) - (a * down * down / 2);
            return Math.Min(stroke.Plan.Length, stroke.Plan.OffsetAt(bump.SpeedUpArrival) + (timing.BurnSpeed * t) + gained);
        }

        return Along(stroke, seconds, timing);
    }

    /// <summary>A stroke under way: one X move from rest to rest along its plan.</summary>
    internal sealed class Stroke(long startX, int direction, long endX, StrokePlan plan)
    {
        /// <summary>The row's Y, microsteps.</summary>
        public long Y { get; init; }

        /// <summary>Index in the plan's moves of the stroke's first move, and how many it runs.</summary>
        public long FirstMoveIndex { get; init; }

        public int MoveCount { get; init; }

        public long StartX { get; } = startX;

        public int Direction { get; } = direction;

        public long EndX { get; } = endX;

        public StrokePlan Plan { get; } = plan;

        /// <summary>When the stroke's offset 0 is, s on the run's clock (its start, moved by the position queries' findings).</summary>
        public double Origin { get; set; }

        /// <summary>How many of its flown gaps' speed-ups were sent (the others the stage crossed at the burn speed).</summary>
        public int GapsFlown { get; set; }
    }
}
