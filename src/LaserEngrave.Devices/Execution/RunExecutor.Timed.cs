using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Programs;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Zaber;
using LaserEngrave.Wire.Scheduling;

namespace LaserEngrave.Devices.Execution;

/// <summary>Timed switching: the optimized plan's strokes and travels sent by <see cref="MotionTimeline"/>, the laser switched by time.</summary>
/// <remarks>
/// A stroke is one X move from rest to rest at the burn speed over a row's run-up, burn runs, crossed gaps and run-out.
/// The stage's Move Absolute is sent so that it arrives a margin after the motion before has ended; a position query
/// follows it, and the laser is switched on only once that has shown the stage moving on its path and every earlier
/// move has reported its end. Then the gate's commands leave so that they take effect as the stage crosses each edge
/// (docs/execution.md). Nothing waits for a reply it does not need: every move's reply is watched against its expected
/// arrival, and one missing or late ends the run, laser off first.
/// </remarks>
public sealed partial class RunExecutor
{
    private readonly Queue<(Move Move, long Index, Task? Acknowledged)> _toComplete = new();
    private string? _timedFault;
    private bool _recoverableFault;
    private double _lastGateWrite;

    // When the gate's wire is free of the lines written so far (the host's estimate at the adapter's mean), and when the
    // last burst stops by itself at the latest (run seconds).
    private double _gateWireFree = double.NegativeInfinity;

    // When the gate's replies to the lines written so far are all in (the same estimate): an off written now is answered after them.
    private double _gateRepliesIn = double.NegativeInfinity;
    private double _burstEndsAt = double.NegativeInfinity;
    private bool _burstEndedItself;
    private LateSwitches? _lateSwitches;
    private long _queuedUpTo = -1;

    // Whether this run's switch-ons are scheduled bursts the gate times (its CAPS? lists AFTER).
    private bool _scheduledBursts;

    // Where the run was when a fault or an abort cut it, for its stop point's cut pixel (under the engine's lock).
    private readonly StrokeCut _cut = new();

    // How late the host may write a timed command before the times after it are moved (below that: the clock's rounding).
    private const double LateSeconds = 0.0001;

    // How late the host has written the current travel's commands so far (a loaded computer on the wall clock).
    private double _travelLate;

    private double TravelLate => _travelLate > LateSeconds ? _travelLate : 0;

    private double RunSeconds => TimeProvider.GetElapsedTime(_engravingStart).TotalSeconds;

    /// <summary>How much later than its round trip an OFF written now is answered, behind the timed lines and replies still on the gate's wire.</summary>
    private double GateQueueSeconds() => _timing is { } timing && _engravingStarted ? timing.OffQueuedSeconds(RunSeconds, _gateWireFree, _gateRepliesIn) : 0;

    /// <summary>
    /// Where this run's own timing puts the stage at <paramref name="timestamp"/> (of <see cref="TimeProvider"/>) from a
    /// timed run's first stroke on: a stroke's motion from when its move arrived, its flown gaps, moved by what the
    /// position queries found, and the travels between strokes on their ramps; null before the first stroke or for any
    /// other kind of run. For a view of the run; it asks the stage nothing.
    /// </summary>
    public StrokePosition? StrokePositionAt(long timestamp)
    {
        lock (_lock)
        {
            return _timing is { } timing && _engravingStarted
                ? _cut.PositionAt(TimeProvider.GetElapsedTime(_engravingStart, timestamp).TotalSeconds, timing)
                : null;
        }
    }

    private async Task ExecuteTimedAsync(RasterProgram program, IEnumerable<RasterStep> steps, long firstIndex, TimedSwitching timing, CancellationToken token)
    {
        _queuedUpTo = firstIndex - 1;
        await BeginEngravingAsync(firstIndex, Options.ResumeFrom?.Row ?? 0, token);
        MotionTimeline? timeline = null;
        foreach (var step in steps)
        {
            if (timeline is null)
            {
                // Reaching the first step's start (the plan's or the resume point's) is not part of the estimate.
                var positioning = TimeProvider.GetTimestamp();
                var (startX, startY) = step.Stroke is { } first ? (first.StartX, first.Y) : (step.Travel.Move.X0, step.Travel.Move.Y0);
                await MoveToAsync(startX, startY, program.Motion.TravelSpeedData, token);
                _notEngraving += TimeProvider.GetElapsedTime(positioning);
                timeline = new MotionTimeline(timing, RunSeconds, _xSpeedData);
            }

            if (IsPauseRequested)
            {
                // Pauses come between steps, with the laser off and the stage at rest.
                await WatchedRepliesAsync(token);
                CompleteAcknowledged();
                await PauseIfAskedAsync(token);
                timeline = new MotionTimeline(timing, RunSeconds, _xSpeedData);
            }

            if (step.Stroke is { } stroke)
            {
                await StrokeAsync(stroke, timing, timeline, token);
            }
            else
            {
                await TravelAsync(step.Travel, timing, timeline, token);
            }
        }

        await WatchedRepliesAsync(token);
        CompleteAcknowledged();
        _accounting.Ended(null, program.Plan.Mask.Height);
    }

    private bool IsPauseRequested
    {
        get
        {
            lock (_lock)
            {
                return _abortSequence is null && _control.PauseRequested;
            }
        }
    }

    private async Task StrokeAsync(StrokeStep stroke, TimedSwitching timing, MotionTimeline timeline, CancellationToken token)
    {
        var plan = stroke.Plan;
        double Offset(long x) => stroke.TimeAt(x);
        long Distance(long x) => stroke.Distance(x);
        var times = timeline.Stroke(plan, stroke.FirstEdgeSeconds, stroke.LastOffSeconds);

        var speedWritten = double.NegativeInfinity;
        if (times.SpeedArrival is { } speedArrival)
        {
            await DelayUntilAsync(speedArrival - timing.StageCommandSeconds, token);
            speedWritten = RunSeconds;
            Watch(Stage.X.SetTargetSpeedAsync(_program.Motion.BurnSpeedData, token), Sent(speedArrival, speedWritten, timing) + timing.StageReplySeconds, "Set Target Speed (X)");
            _xSpeedData = _program.Motion.BurnSpeedData;
        }

        await DelayUntilAsync(times.Arrival - timing.StageCommandSeconds, token);
        ThrowIfAborted();

        // A host late to write (a loaded machine on the wall clock) moves the whole stroke, and everything after it, later.
        var arrival = Math.Max(RunSeconds + timing.StageCommandSeconds, speedWritten + timing.StageCommandSeconds + timing.FrameSeconds);
        if (arrival > times.Arrival + LateSeconds)
        {
            timeline.Delay(arrival - times.Arrival);
            times = times with { Arrival = arrival, End = times.End + (arrival - times.Arrival) };
        }

        var start = stroke.StartX;
        var active = new StrokeCut.Stroke(start, stroke.Direction, stroke.EndX, plan) { Origin = times.Arrival, Y = stroke.Y, FirstMoveIndex = stroke.FirstMoveIndex, MoveCount = stroke.MoveCount };
        lock (_lock)
        {
            _cut.Started(active);
        }

        var earlier = _replies.Unsettled();
        var moveStamped = RunSeconds;
        var move = Stage.X.MoveAbsoluteAfterAsync(stroke.EndX, token);
        var moveWritten = Stage.LineWritten;
        var strokeEnd = Watch(Arrive(move, "X", stroke.EndX, x => _x = x), times.End + timing.StageReplySeconds, "the end of a stroke (X)", axis: "X");
        var strokeEndDeadline = strokeEnd.Deadline;
        var poll = stroke.RunCount > 0 ? Arrival(Stage.X.GetPositionAsync(token)) : null;
        var pollWritten = Stage.LineWritten;
        var direction = stroke.Direction;

        // Where the position queries after flown gaps found the stage ahead (-) or behind (+) its plan, as time at the burn
        // speed; from the start, a move whose write completed late (a computer stalled before it) is that much behind.
        var shift = await WrittenLateAsync(moveWritten, times.Arrival - timing.StageCommandSeconds);
        active.Origin = times.Arrival + shift;

        // The query asked after the move: written later than the move (a stall between them), it finds the stage further on.
        var pollLate = poll is null ? 0 : await WrittenLateAsync(pollWritten, times.Arrival - timing.StageCommandSeconds + shift);
        (StrokePlan.Bump Bump, FlownQuery Query)? flown = null;
        var bumps = plan.Bumps.ToDictionary(b => b.Exit);
        var index = 0;
        for (var k = 0; k < stroke.RunCount; k++)
        {
            var (burn, burnIndex) = stroke.RunAt(k);
            var onWrite = times.Arrival + Offset(burn.X0) + shift + timing.OnDelaySeconds - timing.OnLeadSeconds;
            if (index++ == 0)
            {
                // The round trip counts from the move's write as it completed (a stall before it is no slow reply).
                await ConfirmMovingAsync(earlier, poll!, Math.Max(moveStamped, times.Arrival - timing.StageCommandSeconds + shift), start, direction, timing, onWrite, token, pollLate);
            }
            else if (flown is { } gap)
            {
                shift += await MeasureFlownGapAsync(gap.Bump, gap.Query, start, direction, timing, onWrite, token);
                active.Origin = times.Arrival + shift;

                // Behind its plan (a bump held shorter by a late speed-up), the stroke also ends that much later.
                strokeEnd.Deadline = strokeEndDeadline + Math.Max(0, shift);
                onWrite = times.Arrival + Offset(burn.X0) + shift + timing.OnDelaySeconds - timing.OnLeadSeconds;
                flown = null;
            }

            var offWrite = times.Arrival + Offset(burn.X1) + shift - timing.OffAdvanceSeconds - timing.OffLeadSeconds;

            CompleteUpTo(stroke, burnIndex - 1, null);

            // The burst fills the run from its switch-on to its planned switch-off; its line's length depends on its count.
            var onEffect = onWrite + timing.OnLeadSeconds;
            var offEffect = offWrite + timing.OffLeadSeconds;
            onWrite = timing.BurstWriteSeconds(onEffect, offEffect);
            var (on, onWritten, onAnswered) = _scheduledBursts
                ? await ScheduledSwitchOnAsync(onEffect, offEffect, onWrite, timing, token)
                : await PlainSwitchOnAsync(onEffect, offEffect, onWrite, timing, token);
            lock (_lock)
            {
                _cut.Burning(burn, burnIndex, on, _burstEndsAt);
            }

            _lastGateWrite = Math.Max(onWrite, onWritten);
            WatchGate(on, onAnswered, "the laser gate did not acknowledge the switch-on");
            RunProgress progress;
            lock (_lock)
            {
                _accounting.Current(burn, burnIndex);
                _progress = Snapshot();
                progress = _progress;
            }

            ProgressChanged?.Invoke(this, progress);

            // A scheduled switch-on is written well ahead: when the next one is due before this run's switch-off, the
            // switch-off is left out, since written after that line it would cancel the burst armed by it; the count
            // ends this run by itself.
            var nextWrite = k + 1 < stroke.RunCount && _scheduledBursts && !bumps.ContainsKey(Distance(burn.X1)) ? NextScheduledWrite(stroke.RunAt(k + 1).Move) : double.PositiveInfinity;
            var offLeftOut = offWrite + timing.OffWireSeconds > nextWrite;
            await KeepAlivesUntilAsync(Math.Min(offWrite, nextWrite), timing, token);
            if (offLeftOut)
            {
                _laser.MarkOff(Math.Max(0, offEffect - RunSeconds));
                lock (_lock)
                {
                    _cut.NotBurning();
                }
            }
            else
            {
                await DelayUntilAsync(offWrite, token);

                // A frequency-only gate fires until told otherwise: its switch-off is never left out.
                if (k + 1 < stroke.RunCount && _profile.Gate.CountsBursts && !bumps.ContainsKey(Distance(burn.X1)) && !OffFitsBefore(stroke.RunAt(k + 1).Move, offEffect))
                {
                    // A gap too short for the switch-off's line and the next burst's: the burst ends this run by itself.
                    _laser.MarkOff(timing.OffLeadSeconds);
                    lock (_lock)
                    {
                        _cut.NotBurning();
                    }
                }
                else
                {
                    var (off, offWritten) = await SendSwitchOffAsync(timing);
                    lock (_lock)
                    {
                        _cut.NotBurning();
                    }

                    _lastGateWrite = offWrite;
                    WatchGate(off, Later(offWrite, offWritten) + timing.OffRoundTripSeconds, "the laser gate did not acknowledge the switch-off", switchOff: true);
                    NoteSwitchOffLate(offWrite, offWritten, timing);
                }
            }

            // A run counts as burned once its switch-on is acknowledged (a silent gate burns nothing).
            CompleteUpTo(stroke, burnIndex, on);

            if (bumps.TryGetValue(Distance(burn.X1), out var bump))
            {
                flown = (bump, await FlyGapAsync(bump, times.Arrival + shift, timing, token));
            }
        }

        // When the next run's scheduled switch-on is to be written (as ScheduledSwitchOnAsync will compute it).
        double NextScheduledWrite(Move next)
        {
            var nextOn = times.Arrival + Offset(next.X0) + shift + timing.OnDelaySeconds;
            var nextOff = times.Arrival + Offset(next.X1) + shift - timing.OffAdvanceSeconds;
            return Math.Min(timing.ScheduledWriteSeconds(nextOn, nextOff, _burstEndsAt), timing.BurstWriteSeconds(nextOn, nextOff));
        }

        // Whether the gap after a run carries the switch-off's line ahead of the next burst's (docs/execution.md, "The burst").
        bool OffFitsBefore(Move next, double offEffect)
        {
            var nextOn = times.Arrival + Offset(next.X0) + shift + timing.OnDelaySeconds;
            var nextOff = times.Arrival + Offset(next.X1) + shift - timing.OffAdvanceSeconds;
            return timing.OffFitsBefore(offEffect, nextOn, timing.PulsesWithin(nextOff - nextOn));
        }

        // Behind its plan, the stroke also ends later: the next move must not catch it braking.
        if (shift > 0)
        {
            timeline.Delay(shift);
        }

        CompleteUpTo(stroke, stroke.FirstMoveIndex + stroke.MoveCount - 1, null);
    }

    private async Task TravelAsync(TravelStep travel, TimedSwitching timing, MotionTimeline timeline, CancellationToken token)
    {
        var (move, index) = (travel.Move, travel.MoveIndex);
        var times = timeline.Travel(move.LengthX, move.LengthY);
        var sends = new List<(double Write, Func<Task> Send)>();
        if (times.YArrival is { } yArrival)
        {
            sends.Add((yArrival - timing.StageCommandSeconds, () =>
            {
                Watch(Arrive(Stage.Y.MoveAbsoluteAfterAsync(travel.Y, token), "Y", travel.Y, y => _y = y), times.YEnd + TravelLate + timing.StageReplySeconds, "the end of a travel (Y)", axis: "Y");
                return Task.CompletedTask;
            }));
        }

        if (times.SpeedArrival is { } speedArrival)
        {
            sends.Add((speedArrival - timing.StageCommandSeconds, () =>
            {
                Watch(Stage.X.SetTargetSpeedAsync(travel.SpeedData, token), speedArrival + TravelLate + timing.StageReplySeconds, "Set Target Speed (X)");
                _xSpeedData = travel.SpeedData;
                return Task.CompletedTask;
            }));
        }

        if (times.XArrival is { } xArrival)
        {
            sends.Add((xArrival - timing.StageCommandSeconds, () =>
            {
                Watch(Arrive(Stage.X.MoveAbsoluteAfterAsync(travel.X, token), "X", travel.X, x => _x = x), times.XEnd + TravelLate + timing.StageReplySeconds, "the end of a travel (X)", axis: "X");
                return Task.CompletedTask;
            }));
        }

        lock (_lock)
        {
            _cut.Travelling(move, index, times.XArrival, times.YArrival);
        }

        foreach (var (write, send) in sends.OrderBy(s => s.Write))
        {
            await DelayUntilAsync(write, token);
            ThrowIfAborted();
            _travelLate = Math.Max(_travelLate, RunSeconds - write);
            await send();
            _travelLate = Math.Max(_travelLate, await WrittenLateAsync(Stage.LineWritten, write));
        }

        if (_travelLate > LateSeconds)
        {
            // A host late to write (a loaded computer) moves this travel's ends, and everything after them, later.
            timeline.Delay(_travelLate, travel: true);
            lock (_lock)
            {
                _cut.Travelling(move, index, times.XArrival + _travelLate, times.YArrival + _travelLate);
            }
        }

        _travelLate = 0;

        _accounting.Current(move, index);

        CompleteUp(move, index, null);
    }

    /// <summary>
    /// Flies a gap (docs/execution.md, "Flown gaps"): the travel speed set just after the exit edge, the burn speed set back,
    /// then a position query once the stage is surely at the burn speed again; returns the query.
    /// </summary>
    private async Task<FlownQuery> FlyGapAsync(StrokePlan.Bump bump, double start, TimedSwitching timing, CancellationToken token)
    {
        var upWrite = start + bump.SpeedUpArrival - timing.StageCommandSeconds;
        await DelayUntilAsync(upWrite, token);
        ThrowIfAborted();
        var upLate = RunSeconds - upWrite;
        Watch(Stage.X.SetTargetSpeedAsync(_program.Motion.TravelSpeedData, token), Sent(start + bump.SpeedUpArrival, RunSeconds, timing) + timing.StageReplySeconds, "Set Target Speed (X, a flown gap)");
        var upWritten = Stage.LineWritten;
        NoteGapFlown();
        var downWrite = start + bump.SpeedDownArrival - timing.StageCommandSeconds;
        await DelayUntilAsync(downWrite, token);

        // A write that completed late (a computer stalled before it) left that late, whatever the clock said before it.
        upLate = Math.Max(upLate, await WrittenLateAsync(upWritten, upWrite));
        var downLate = RunSeconds - downWrite;
        Watch(Stage.X.SetTargetSpeedAsync(_program.Motion.BurnSpeedData, token), Sent(start + bump.SpeedDownArrival, RunSeconds, timing) + timing.StageReplySeconds, "Set Target Speed (X, after a flown gap)");
        downLate = Math.Max(downLate, await WrittenLateAsync(Stage.LineWritten, downWrite));

        // The query goes once the stage is surely back at the burn speed: never sooner after the speed-down than planned,
        // and later still when the speed-down left late against the speed-up (a busy computer): held longer, the bump
        // peaks higher and takes that much longer to come back down, and a query before that would find the stage still
        // fast, take it for behind its plan, and the laser would come on early.
        var hold = bump.SpeedDownArrival - bump.SpeedUpArrival;
        var longer = Later(0, downLate) - Later(0, upLate);
        var rampDown = longer > 0 ? (Rise(timing, hold + longer) - Rise(timing, hold)) / timing.Acceleration : 0;
        var queryWrite = start + bump.QueryArrival - timing.StageCommandSeconds;
        await DelayUntilAsync(Math.Max(queryWrite, RunSeconds + (bump.QueryArrival - bump.SpeedDownArrival) + rampDown), token);
        var queryLate = RunSeconds - queryWrite;
        var queryStamped = RunSeconds;
        var query = Arrival(Stage.X.GetPositionAsync(token));
        var queryWrittenLate = await WrittenLateAsync(Stage.LineWritten, queryWrite);
        queryLate = Math.Max(queryLate, queryWrittenLate);

        // Its round trip counts from the write's completion: a stall before the write is the host's, not the reply's.
        return new FlownQuery(query, Math.Max(queryStamped, queryWrite + queryWrittenLate), Later(0, upLate), Later(0, downLate), Later(0, queryLate));
    }

    /// <summary>How far above the burn speed a bump held <paramref name="hold"/> s rises (<see cref="TimedSwitching.FlyGain"/>'s dV).</summary>
    private static double Rise(TimedSwitching timing, double hold) =>
        Math.Min(timing.Acceleration * Math.Max(0, hold), Math.Max(0, timing.TravelSpeed - timing.BurnSpeed));

    /// <summary>A flown gap's position query, and how late (s) the host wrote the speed-up, the speed-down and the query.</summary>
    private sealed record FlownQuery(Answered<long> Query, double WrittenSeconds, double UpLate, double DownLate, double QueryLate);

    /// <summary>A reply and when it came in (run seconds; NaN until then), so that it is judged by its round trip as well as by what it says.</summary>
    private sealed class Answered<T>(Task<T> task)
    {
        public Task<T> Task { get; } = task;

        public double Seconds { get; set; } = double.NaN;
    }

    /// <summary>Stamps a reply's arrival on the run clock when its task completes (before anything awaiting it runs).</summary>
    private Answered<T> Arrival<T>(Task<T> task)
    {
        var arrived = new Answered<T>(task);
        _ = task.ContinueWith(_ => arrived.Seconds = RunSeconds, CancellationToken.None, TaskContinuationOptions.ExecuteSynchronously, TaskScheduler.Default);
        return arrived;
    }

    /// <summary>
    /// A position reply that came back too late to locate the stage (issue 34): its round trip from <paramref name="written"/>
    /// past what the links allow (<paramref name="frames"/> frames on the wire each way, both adapters and their spreads, a
    /// margin), so when the axis answered is not known and its position says nothing of where the stage is against its
    /// plan. A timing doubt with the laser off, never "ahead of plan".
    /// </summary>
    private void ThrowIfReplyTooLate<T>(Answered<T> reply, double written, int frames, TimedSwitching timing, string what)
    {
        var roundTrip = reply.Seconds - written;
        var expected = timing.StageAdapterSeconds + (frames * timing.FrameSeconds) + timing.StageReplySeconds;
        var allowed = expected + (4 * timing.StageJitterSeconds) + ReplyMarginSeconds;
        if (roundTrip > allowed)
        {
            throw Fault(
                string.Create(CultureInfo.InvariantCulture, $"the X axis' reply to {what} came back {Units.SecondsToMs(roundTrip):0.0} ms after it was written ({Units.SecondsToMs(expected):0.0} ms expected): too late to locate the stage, so the laser stays off"),
                recoverable: true);
        }
    }

    // What a position reply's round trip may exceed its links' spread by (the host's own reaction to the reply).
    private const double ReplyMarginSeconds = 0.002;

    /// <summary>
    /// After a flown gap, before the next switch-on: the position query's answer says how far ahead of its plan the stage
    /// is (the speed changes' latencies); returns the time shift that puts the next switchings back on their edges.
    /// </summary>
    private async Task<double> MeasureFlownGapAsync(StrokePlan.Bump bump, FlownQuery flown, long start, int direction, TimedSwitching timing, double onWrite, CancellationToken token)
    {
        var query = flown.Query.Task;
        if (!await CompletesByAsync(query, onWrite, token) || !query.IsCompletedSuccessfully)
        {
            throw Fault("the X axis did not answer the position query after a flown gap before the laser was to come on", recoverable: true);
        }

        ThrowIfReplyTooLate(flown.Query, flown.WrittenSeconds, 1, timing, "the position query after a flown gap");

        // A host late to write (a loaded computer) held the bump longer or shorter and asked later: where the stage then is.
        var hold = bump.SpeedDownArrival - bump.SpeedUpArrival;
        var gainedMore = timing.FlyGain(hold + flown.DownLate - flown.UpLate) - timing.FlyGain(hold);
        var expected = bump.ExpectedOffset + (timing.BurnSpeed * flown.QueryLate) + gainedMore;
        var ahead = ((query.Result - start) * direction) - expected;
        if (Math.Abs(ahead) > bump.MaxErrorMicrosteps + 1)
        {
            // The latencies spread wider than assumed. One check sees one or two draws of them and rarely their largest, so
            // the run that goes on from here assumes twice what this one found (RunResult.LatencyScale).
            _latencyScaleSeen = Math.Max(_latencyScaleSeen, Math.Min(MaxLatencyScale, 2 * LatencyScale * Math.Abs(ahead) / Math.Max(bump.MaxErrorMicrosteps, 1)));

            throw Fault(string.Create(
                System.Globalization.CultureInfo.InvariantCulture,
                $"the X axis reported {query.Result} microsteps after a flown gap, {ahead:0} from its plan (at most {bump.MaxErrorMicrosteps:0} expected): it is not moving as planned, so the laser stays off"),
                recoverable: true);
        }

        // What the bump gained beyond its plan (its speed commands' real interval) is the stage ahead of its plan as surely as
        // what the query found: every later switching comes that much sooner. Asking later is not: it is only time passing.
        return -(ahead + gainedMore) / timing.BurnSpeed;
    }

    /// <summary>Before the first switch-on of a stroke: every earlier move has reported its end, and the position query shows the stage on its way.</summary>
    private async Task ConfirmMovingAsync(IReadOnlyList<ReplyWatch.Watched> earlier, Answered<long> arrived, double moveWritten, long start, int direction, TimedSwitching timing, double onWrite, CancellationToken token, double pollLate = 0)
    {
        var poll = arrived.Task;
        foreach (var watched in earlier)
        {
            // A move whose end is never reported is settled by the next move of its axis reporting its own.
            if (!await CompletesByAsync(watched.Settled(), onWrite, token))
            {
                throw Fault($"the stage had not reported {watched.What} when the laser was to come on", recoverable: true);
            }
        }

        if (!await CompletesByAsync(poll, onWrite, token))
        {
            throw Fault("the X axis did not answer the position query before the laser was to come on", recoverable: true);
        }

        long position;
        try
        {
            position = await poll;
        }
        catch (DeviceException ex)
        {
            throw Fault($"the X axis did not answer the position query before the laser was to come on: {ex.Message}");
        }

        // The stroke's Move Absolute and its query together: the query's frame leaves behind the move's.
        ThrowIfReplyTooLate(arrived, moveWritten + pollLate, 2, timing, "the position query after a stroke's Move Absolute");

        // The query arrives one frame after the move: the stage has accelerated that long, give or take both latencies.
        var a = timing.Acceleration;
        var earliest = Math.Max(0, timing.FrameSeconds + pollLate - (2 * timing.StageJitterSeconds));
        var latest = timing.FrameSeconds + pollLate + (2 * timing.StageJitterSeconds);
        var moved = (position - start) * direction;
        var least = Math.Max(1, Math.Floor(0.5 * a * earliest * earliest / 2));
        var most = Math.Ceiling(0.5 * a * latest * latest) + 2;
        if (moved < least && moved >= 0 && RunSeconds + timing.FrameSeconds + timing.StageReplySeconds + (2 * timing.StageJitterSeconds) < onWrite)
        {
            // Not yet seen moving (the query overtook the move's start on a late device, or on a simulator on the wall
            // clock): ask once more while there is time; the laser stays off until it has been seen moving.
            var againWritten = RunSeconds;
            var againArrived = Arrival(Stage.X.GetPositionAsync(token));
            var again = againArrived.Task;
            if (await CompletesByAsync(again, onWrite, token) && again.IsCompletedSuccessfully)
            {
                ThrowIfReplyTooLate(againArrived, againWritten, 1, timing, "a second position query at a stroke's start");
                position = again.Result;
                moved = (position - start) * direction;
                least = 1;
                most = Math.Abs(Job!.Plan.Geometry.TravelXMicrosteps);
            }
        }

        if (moved < least || moved > most)
        {
            throw Fault($"the X axis reported {position} microsteps just after starting its stroke, not {start + (direction * least)}..{start + (direction * most)}: it is not moving as planned, so the laser stays off");
        }
    }

    private Task<bool> CompletesByAsync(Task task, double seconds, CancellationToken token) => _replies.CompletesByAsync(task, seconds, token);

    private async Task KeepAlivesUntilAsync(double offWrite, TimedSwitching timing, CancellationToken token)
    {
        var period = GateKeepAlive.PeriodFor(_profile.Gate.WatchdogMs, Options.KeepAliveFraction).TotalSeconds;
        if (period <= 0)
        {
            return;
        }

        while (true)
        {
            var next = Math.Max(_lastGateWrite + period, RunSeconds);
            if (next + timing.KeepAliveRoundTripSeconds + (2 * timing.GateJitterSeconds) + 0.001 >= offWrite)
            {
                return;
            }

            await DelayUntilAsync(next, token);
            _lastGateWrite = RunSeconds;
            _gateWireFree = timing.GateWireFreeAfter(_lastGateWrite, _gateWireFree, timing.KeepAliveBytes);
            _gateRepliesIn = timing.GateRepliesInAfter(_gateWireFree, _gateRepliesIn, timing.KeepAliveReplyBytes);
            WatchGate(Gate.KeepAliveAsync(CancellationToken.None), _lastGateWrite + timing.KeepAliveRoundTripSeconds, "the laser gate did not answer the keepalive");
        }
    }

    /// <summary>
    /// Sends a timed switch-on under the laser lock (after checking for an abort) and returns its acknowledgement without
    /// waiting for it, and when it was written: the lock is free again at once, so an abort's or a fault's switch-off never
    /// waits behind it. The switch-on is the gate's counted burst, sized now, from the real write time and the gate's wire
    /// queue, to stop by itself before <paramref name="offEffect"/> (docs/execution.md, "The burst"): a switch-off that is
    /// late, refused or lost then costs no pulse past the edge. A host so late that it is beyond the profile's edge
    /// tolerance (or that no pulse fits any more) leaves the laser off and ends the run as a timing doubt.
    /// </summary>
    private async Task<(Task Acknowledged, double WrittenSeconds)> SendSwitchOnAsync(double onEffect, double offEffect, TimedSwitching timing)
    {
        var sent = await SendSwitchOnLockedAsync(onEffect, offEffect, timing);
        await LateWrite.CheckAsync(sent.LineWritten, TimeProvider, _engravingStart, sent.WrittenSeconds, sent.LateSeconds, timing, _profile.EdgeToleranceUm, "switch the laser on", m => Fault(m, recoverable: true));
        return (sent.Acknowledged, sent.WrittenSeconds);
    }

    private async Task<(Task Acknowledged, double WrittenSeconds, double LateSeconds, Task<long?> LineWritten)> SendSwitchOnLockedAsync(double onEffect, double offEffect, TimedSwitching timing)
    {
        await _laser.Lock.WaitAsync();
        try
        {
            ThrowIfAborted();
            if (_fault.IsCancellationRequested)
            {
                throw new DeviceException(_timedFault ?? "a fault ended the run");
            }

            // Late is when the gate will start firing against when it was to: the host's own lateness and any line still
            // on the gate's wire ahead of this one.
            var written = RunSeconds;
            var pulses = timing.BurstPulses(written, _gateWireFree, offEffect);
            var late = timing.GateWireFreeAfter(written, _gateWireFree, timing.BurstCommand(Math.Max(1, pulses)).Length) + timing.GateProcessingSeconds - onEffect;
            var lateUm = late * timing.BurnSpeed * timing.MicrostepUm;
            if (lateUm > _profile.EdgeToleranceUm || pulses < 1)
            {
                throw Fault(
                    string.Create(CultureInfo.InvariantCulture, $"this computer was {Units.SecondsToMs(late):0.0} ms late to switch the laser on, {lateUm:0.0} µm at the burn speed, beyond the profile's edge tolerance of {_profile.EdgeToleranceUm:0.###} µm: the laser stayed off for that run"),
                    recoverable: true);
            }

            if (late > LateSeconds)
            {
                NoteLateSwitch(lateUm);
            }

            // A frequency-only gate is switched on by its frequency alone, as before the burst: only the timed switch-off ends the run.
            var counted = _profile.Gate.CountsBursts;
            var ack = counted ? Gate.BurstAsync(pulses, timing.FrequencyHz, CancellationToken.None) : Gate.SetFrequencyAsync(timing.FrequencyHz, CancellationToken.None);
            var lineWritten = Gate.LineWritten;
            _gateWireFree = timing.GateWireFreeAfter(written, _gateWireFree, timing.BurstCommand(pulses).Length);
            _gateRepliesIn = timing.GateRepliesInAfter(_gateWireFree, _gateRepliesIn, timing.BurstReplyBytes(pulses));
            var firing = _gateWireFree + timing.GateProcessingSeconds;
            lock (_lock)
            {
                _laser.MarkOn(TimeProvider.GetTimestamp() + (long)((firing - written) * TimeProvider.TimestampFrequency));
                _burstEndsAt = counted ? firing + ((double)pulses / timing.FrequencyHz) + timing.GateJitterSeconds : double.PositiveInfinity;
            }

            return (ack, written, Math.Max(0, late), lineWritten);
        }
        finally
        {
            _laser.Lock.Release();
        }
    }

    /// <summary>A plain switch-on (<c>BURST</c>, or <c>FREQ</c> on a frequency-only gate), written when its line must leave: the host's lateness is its edge's.</summary>
    /// <returns>Its acknowledgement, when it was written, and when its acknowledgement is expected (run seconds).</returns>
    private async Task<(Task Acknowledged, double WrittenSeconds, double AnsweredSeconds)> PlainSwitchOnAsync(double onEffect, double offEffect, double onWrite, TimedSwitching timing, CancellationToken token)
    {
        await DelayUntilAsync(onWrite, token);
        var (on, written) = await SendSwitchOnAsync(onEffect, offEffect, timing);
        return (on, written, Later(onWrite, written) + timing.OnRoundTripSeconds);
    }

    /// <summary>
    /// A switch-on the gate times itself (<c>BURST n hz AFTER us</c>, docs/laser-gate-protocol.md "Scheduled bursts"):
    /// written its slack ahead of time, with the delay computed at the write from when it is written, the lines still on
    /// the gate's wire and the gate's processing, so that a host late by less than the slack moves no edge. Written too
    /// late for that, it is the plain switch-on at its own time, with the edge tolerance as before.
    /// </summary>
    private async Task<(Task Acknowledged, double WrittenSeconds, double AnsweredSeconds)> ScheduledSwitchOnAsync(double onEffect, double offEffect, double onWrite, TimedSwitching timing, CancellationToken token)
    {
        await DelayUntilAsync(Math.Min(timing.ScheduledWriteSeconds(onEffect, offEffect, _burstEndsAt), onWrite), token);
        for (var attempt = 0; attempt < 3; attempt++)
        {
            if (await SendScheduledSwitchOnAsync(onEffect, offEffect, timing) is { } sent)
            {
                // Its delay was computed at the stamp: a write that completed later (a computer stalled between them)
                // reached the gate that much later and fires that much late, its count ending past the edge. Beyond the
                // tolerance that is a timing doubt: the fault's OFF cancels the armed burst before or as it fires.
                await LateWrite.CheckAsync(sent.LineWritten, TimeProvider, _engravingStart, sent.WrittenSeconds, 0, timing, _profile.EdgeToleranceUm, "switch the laser on", m => Fault(m, recoverable: true));
                return (sent.Acknowledged, sent.WrittenSeconds, sent.AnsweredSeconds);
            }

            // A delay just at a power of ten (its digits and the line's length disagree) is tried again a moment later.
            var again = RunSeconds + (2 * timing.GateByteSeconds);
            if (again >= onWrite)
            {
                break;
            }

            await DelayUntilAsync(again, token);
        }

        return await PlainSwitchOnAsync(onEffect, offEffect, onWrite, timing, token);
    }

    /// <summary>Writes a scheduled switch-on under the laser lock if it is still in time for the gate's timer; null when not (nothing written).</summary>
    private async Task<(Task Acknowledged, double WrittenSeconds, double AnsweredSeconds, Task<long?> LineWritten)?> SendScheduledSwitchOnAsync(double onEffect, double offEffect, TimedSwitching timing)
    {
        await _laser.Lock.WaitAsync();
        try
        {
            ThrowIfAborted();
            if (_fault.IsCancellationRequested)
            {
                throw new DeviceException(_timedFault ?? "a fault ended the run");
            }

            // Computed at the write itself: whatever the host lost before it comes off the delay, not off the edge.
            var written = RunSeconds;
            if (timing.Schedule(written, _gateWireFree, onEffect, offEffect) is not { } burst)
            {
                return null;
            }

            var ack = Gate.BurstAfterAsync(burst.Pulses, timing.FrequencyHz, burst.AfterUs, CancellationToken.None);
            var lineWritten = Gate.LineWritten;
            _gateWireFree = burst.ArrivalSeconds;
            _gateRepliesIn = timing.GateRepliesInAfter(_gateWireFree, _gateRepliesIn, timing.BurstAfterReplyBytes(burst.Pulses, burst.AfterUs));
            var firing = burst.ArrivalSeconds + (burst.AfterUs / 1e6);
            lock (_lock)
            {
                _laser.MarkOn(TimeProvider.GetTimestamp() + (long)((firing - written) * TimeProvider.TimestampFrequency));
                _burstEndsAt = firing + ((double)burst.Pulses / timing.FrequencyHz) + timing.GateJitterSeconds;
            }

            return (ack, written, _gateRepliesIn + timing.GateJitterSeconds, lineWritten);
        }
        finally
        {
            _laser.Lock.Release();
        }
    }

    /// <summary>How much later than <paramref name="plannedWrite"/> (run seconds) a command's write completed; 0 when on time or unknown.</summary>
    private async Task<double> WrittenLateAsync(Task<long?> lineWritten, double plannedWrite) =>
        await lineWritten is { } stamp && TimeProvider.GetElapsedTime(_engravingStart, stamp).TotalSeconds - plannedWrite is > LateSeconds and var late ? late : 0;

    /// <summary>Sends a timed switch-off under the laser lock and returns its acknowledgement without waiting for it, and when it was written.</summary>
    private async Task<(Task Acknowledged, double WrittenSeconds)> SendSwitchOffAsync(TimedSwitching timing)
    {
        await _laser.Lock.WaitAsync();
        try
        {
            var written = RunSeconds;

            // Counted from effect to effect: the switch-off takes effect its lead after it is sent, as the switch-on did.
            var off = Gate.OffAsync(CancellationToken.None);
            _gateWireFree = timing.GateWireFreeAfter(written, _gateWireFree, timing.OffCommand.Length);
            _gateRepliesIn = timing.GateRepliesInAfter(_gateWireFree, _gateRepliesIn, timing.OffReplyBytes);
            _laser.MarkOff(timing.OffLeadSeconds);
            return (off, written);
        }
        finally
        {
            _laser.Lock.Release();
        }
    }

    /// <summary>A switch-on sent late but within the edge tolerance, or a late switch-off: counted for the run's log and summary.</summary>
    private void NoteLateSwitch(double lateUm, bool off = false)
    {
        lock (_lock)
        {
            _lateSwitches = LateSwitches.Add(_lateSwitches, off ? new LateSwitches(0, 0, _profile.EdgeToleranceUm, 1) : new LateSwitches(1, lateUm, _profile.EdgeToleranceUm));
        }
    }

    /// <summary>
    /// A switch-off written late: the burst has stopped the laser by itself at the run's end already, so no pulse crossed
    /// the edge; it is counted and logged, beside the late switch-ons. A frequency-only gate has no burst: beyond the edge
    /// tolerance its laser fired past the edge, and the run ends.
    /// </summary>
    private void NoteSwitchOffLate(double planned, double written, TimedSwitching timing)
    {
        var late = written - planned;
        if (late > LateSeconds)
        {
            var lateUm = late * timing.BurnSpeed * timing.MicrostepUm;
            NoteLateSwitch(lateUm, off: true);
            if (!_profile.Gate.CountsBursts && lateUm > _profile.EdgeToleranceUm)
            {
                // A frequency-only gate fires until the switch-off arrives: late beyond the tolerance, it fired past the edge.
                throw Fault(string.Create(
                    CultureInfo.InvariantCulture,
                    $"this computer was {Units.SecondsToMs(late):0.0} ms late to switch the laser off, {lateUm:0.0} µm at the burn speed, beyond the profile's edge tolerance of {_profile.EdgeToleranceUm:0.###} µm: this frequency-only gate fired past the run's exit edge"));
            }
        }
    }

    /// <summary>When a stage command planned to arrive at <paramref name="plannedArrival"/> arrives, written at <paramref name="writtenSeconds"/>.</summary>
    /// <remarks>A host late to write (a loaded computer) is not the device's delay: its reply is expected that much later.</remarks>
    private static double Sent(double plannedArrival, double writtenSeconds, TimedSwitching timing) =>
        Later(plannedArrival, writtenSeconds + timing.StageCommandSeconds);

    // The actual time when it is later than planned by more than the clock's rounding, else the planned one.
    private static double Later(double planned, double actual) => actual > planned + LateSeconds ? actual : planned;

    /// <param name="switchOff">A switch-off: refused or unanswered, the laser may still fire, so the fault takes every path to off.</param>
    private void WatchGate(Task reply, double expectedSeconds, string what, bool switchOff = false)
    {
        Watch(reply, expectedSeconds, what, gate: true, switchOff: switchOff);

        // When the gate last showed it was alive: its reply left it a reply's wire and adapter time before it came in.
        _ = reply.ContinueWith(
            answered =>
            {
                if (answered.IsCompletedSuccessfully && _program is RasterProgram { Timing: { } timing })
                {
                    var left = RunSeconds - (timing.OnRoundTripSeconds - timing.OnLeadSeconds) - timing.GateJitterSeconds;
                    lock (_lock)
                    {
                        _cut.GateAlive(left);
                    }
                }
            },
            CancellationToken.None,
            TaskContinuationOptions.ExecuteSynchronously,
            TaskScheduler.Default);
    }

    private async Task DelayUntilAsync(double seconds, CancellationToken token)
    {
        var wait = seconds - RunSeconds;
        if (wait > 0)
        {
            await PreciseDelay.DelayAsync(TimeProvider, TimeSpan.FromSeconds(wait), token);
        }

        token.ThrowIfCancellationRequested();
    }

    private static async Task Arrive(Task<long> move, string axis, long target, Action<long> arrived)
    {
        var position = await move;
        arrived(Arrived(axis, position, target));
    }

    /// <summary>Watches a reply (<see cref="ReplyWatch.Watch"/>): late past its expected arrival, failed or wrong, it ends the run, laser off first.</summary>
    private ReplyWatch.Watched Watch(Task reply, double expectedSeconds, string what, bool gate = false, string? axis = null, bool switchOff = false) =>
        _replies.Watch(reply, expectedSeconds, what, gate, axis, switchOff);

    // Every reply watched so far, each by its deadline (a move never reported is settled by the next of its axis).
    private async Task WatchedRepliesAsync(CancellationToken token)
    {
        await _replies.AllSettledAsync(token);
        lock (_lock)
        {
            if (_timedFault is { } fault)
            {
                throw new DeviceException(fault);
            }
        }

        _replies.Clear();
    }

    /// <summary>A fault found while commands are in flight: the laser goes off at once, then the run ends as failed; returns the exception to throw.</summary>
    private DeviceException Fault(string reason) => Fault(reason, recoverable: false);

    /// <param name="reason">The run's fault, one line.</param>
    /// <param name="recoverable">Only a doubt about time (a position query or a stage reply too late, a switch-on past the tolerance), never about the laser: see <see cref="RunResult.Recoverable"/>.</param>
    private DeviceException Fault(string reason, bool recoverable)
    {
        var first = false;
        lock (_lock)
        {
            if (_timedFault is null)
            {
                _timedFault = reason;
                _recoverableFault = recoverable;
                first = true;
            }
            else if (!recoverable)
            {
                // Anything else found while the first fault is handled is not a mere timing doubt.
                _recoverableFault = false;
            }
        }

        if (first)
        {
            _ = TaskRunner.For(TimeProvider).Start(_laser.OffSafelyAsync);
            _fault.Cancel();
        }

        return new DeviceException(reason);
    }

    private void CompleteUpTo(StrokeStep stroke, long index, Task? lastAcknowledged)
    {
        for (var i = 0; i < stroke.MoveCount && stroke.FirstMoveIndex + i <= index; i++)
        {
            Queue(stroke.MoveAt(i), stroke.FirstMoveIndex + i, index, lastAcknowledged);
        }

        CompleteAcknowledged();
    }

    private void CompleteUp(Move move, long index, Task? lastAcknowledged)
    {
        Queue(move, index, index, lastAcknowledged);
        CompleteAcknowledged();
    }

    private void Queue(Move move, long moveIndex, long index, Task? lastAcknowledged)
    {
        if (moveIndex > _queuedUpTo)
        {
            _toComplete.Enqueue((move, moveIndex, moveIndex == index ? lastAcknowledged : null));
            _queuedUpTo = moveIndex;
        }
    }

    /// <summary>Raises completion, in order, for every queued move whose switch-on (if it has one) is acknowledged.</summary>
    private void CompleteAcknowledged()
    {
        while (_toComplete.TryPeek(out var next) && (next.Acknowledged is null || next.Acknowledged.IsCompletedSuccessfully))
        {
            _toComplete.Dequeue();
            Completed(next.Move, next.Index);
        }
    }

    /// <summary>The stop point's cut pixel when a timed raster run was cut in the middle of a burn run (<see cref="StrokeCut.Cut"/>). Caller holds the lock.</summary>
    private RunStopPoint CutWithin(RunStopPoint stop) =>
        _program is RasterProgram { Timing: { } timing }
            ? _cut.Cut(stop, timing, Job!.Plan, _laser.OffConfirmed, _profile.Gate.WatchdogMs, _stoppedAtKnownPosition ? _x : null, SwitchOnRefused)
            : _program is RasterProgram ? StepCut(stop) : stop;

    // A flown gap's speed-up has been sent: from here the stroke's plan holds that gap.
    private void NoteGapFlown()
    {
        lock (_lock)
        {
            _cut.GapFlown();
        }
    }

    /// <summary>Whether the gate refused the switch-on (an error reply): the laser did not come on for that run.</summary>
    private bool SwitchOnRefused(Task acknowledged) =>
        acknowledged.Exception?.InnerException is LaserGate.LaserGateException refusal
        && _profile.Gate.ErrorPrefix.Length > 0 && refusal.Reply.StartsWith(_profile.Gate.ErrorPrefix, StringComparison.Ordinal);

    /// <summary>
    /// Before the stop point: a switch-on whose acknowledgement is still on its way (a late reply) is waited for, at
    /// most the gate's own timeout, so that a late "OK" says the run was burned up to the fault's switch-off.
    /// </summary>
    private async Task SettleSwitchOnAsync()
    {
        Task? acknowledged;
        lock (_lock)
        {
            acknowledged = _cut.SwitchOnAcknowledged;
        }

        if (acknowledged is { IsCompleted: false })
        {
            using var stop = new CancellationTokenSource();
            await Task.WhenAny(acknowledged, PreciseDelay.DelayAsync(TimeProvider, TimeSpan.FromMilliseconds(_profile.Gate.TimeoutMs), stop.Token));
            stop.Cancel();
        }
    }

    /// <summary>The X axis' reply to the stop after a fault: whether it stopped where the stroke's motion put it (<see cref="StrokeCut.Stopped"/>).</summary>
    private void NoteStopped(double written, long position)
    {
        lock (_lock)
        {
            if (_program is RasterProgram { Timing: { } timing })
            {
                _cut.Stopped(written, position, timing);
            }
        }
    }
}
