using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
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
    private string? _timedFault;
    private bool _recoverableFault;

    // Where the run was when a fault or an abort cut it, for its stop point's cut pixel (under the engine's lock).
    private readonly StrokeCut _cut = new();

    // How late the host may write a timed command before the times after it are moved (below that: the clock's rounding).
    private const double LateSeconds = GateSwitching.LateSeconds;

    // How late the host has written the current travel's commands so far (a loaded computer on the wall clock).
    private double _travelLate;

    private double TravelLate => _travelLate > LateSeconds ? _travelLate : 0;

    private double RunSeconds => TimeProvider.GetElapsedTime(_engravingStart).TotalSeconds;

    /// <summary>How much later than its round trip an OFF written now is answered, behind the timed lines and replies still on the gate's wire.</summary>
    private double GateQueueSeconds() => _timing is { } timing && _engravingStarted ? _switching.QueueSeconds(timing, RunSeconds) : 0;

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
        _completions.StartAt(firstIndex);
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
                _completions.Acknowledged();
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
        _completions.Acknowledged();
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
        var s = await StartStrokeAsync(stroke, timing, timeline, token);
        for (var k = 0; k < stroke.RunCount; k++)
        {
            await BurnRunAsync(s, k, token);
        }

        // Behind its plan, the stroke also ends later: the next move must not catch it braking.
        if (s.Shift > 0)
        {
            timeline.Delay(s.Shift);
        }

        _completions.UpTo(stroke, stroke.FirstMoveIndex + stroke.MoveCount - 1, null);
    }

    /// <summary>Sends a stroke's speed and its Move Absolute with the position query behind it, at their times (later, with everything after, when the host is late).</summary>
    private async Task<StrokeUnderWay> StartStrokeAsync(StrokeStep stroke, TimedSwitching timing, MotionTimeline timeline, CancellationToken token)
    {
        var times = timeline.Stroke(stroke.Plan, stroke.FirstEdgeSeconds, stroke.LastOffSeconds);
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

        var active = new StrokeCut.Stroke(stroke.StartX, stroke.Direction, stroke.EndX, stroke.Plan) { Origin = times.Arrival, Y = stroke.Y, FirstMoveIndex = stroke.FirstMoveIndex, MoveCount = stroke.MoveCount };
        lock (_lock)
        {
            _cut.Started(active);
        }

        var earlier = _replies.Unsettled();
        var moveStamped = RunSeconds;
        var move = Stage.X.MoveAbsoluteAfterAsync(stroke.EndX, token);
        var moveWritten = Stage.LineWritten;
        var strokeEnd = Watch(Arrive(move, "X", stroke.EndX, x => _x = x), times.End + timing.StageReplySeconds, "the end of a stroke (X)", axis: "X");
        var poll = stroke.RunCount > 0 ? _position.Arrival(Stage.X.GetPositionAsync(token)) : null;
        var pollWritten = Stage.LineWritten;
        var s = new StrokeUnderWay(stroke, timing, times, active) { End = strokeEnd, EndDeadline = strokeEnd.Deadline, Earlier = earlier, Poll = poll, MoveStamped = moveStamped };
        s.Shift = await WrittenLateAsync(moveWritten, times.Arrival - timing.StageCommandSeconds);
        active.Origin = times.Arrival + s.Shift;

        // The query asked after the move: written later than the move (a stall between them), it finds the stage further on.
        s.PollLate = poll is null ? 0 : await WrittenLateAsync(pollWritten, times.Arrival - timing.StageCommandSeconds + s.Shift);
        return s;
    }

    /// <summary>Burn run <paramref name="k"/> of a stroke: the stage checked where it must be, the switch-on, the switch-off (or the burst's own end), the gap after it flown.</summary>
    private async Task BurnRunAsync(StrokeUnderWay s, int k, CancellationToken token)
    {
        var (stroke, timing, times) = (s.Stroke, s.Timing, s.Times);
        var (burn, burnIndex) = stroke.RunAt(k);
        var onWrite = s.OnWrite(burn.X0);
        if (k == 0)
        {
            // The round trip counts from the move's write as it completed (a stall before it is no slow reply).
            await _position.ConfirmMovingAsync(s.Earlier, s.Poll!, Math.Max(s.MoveStamped, times.Arrival - timing.StageCommandSeconds + s.Shift), stroke.StartX, stroke.Direction, timing, onWrite, token, s.PollLate);
        }
        else if (s.Flown is { } gap)
        {
            s.Shift += await _position.MeasureFlownGapAsync(gap.Bump, gap.Query, stroke.StartX, stroke.Direction, timing, onWrite, token);
            s.Active.Origin = times.Arrival + s.Shift;

            // Behind its plan (a bump held shorter by a late speed-up), the stroke also ends that much later.
            s.End.Deadline = s.EndDeadline + Math.Max(0, s.Shift);
            onWrite = s.OnWrite(burn.X0);
            s.Flown = null;
        }

        var offWrite = s.OffWrite(burn.X1);
        _completions.UpTo(stroke, burnIndex - 1, null);

        // The burst fills the run from its switch-on to its planned switch-off; its line's length depends on its count.
        var onEffect = onWrite + timing.OnLeadSeconds;
        var offEffect = offWrite + timing.OffLeadSeconds;
        onWrite = timing.BurstWriteSeconds(onEffect, offEffect);
        var (on, onWritten, onAnswered) = _switching.ScheduledBursts
            ? await _switching.ScheduledSwitchOnAsync(onEffect, offEffect, onWrite, timing, token)
            : await _switching.PlainSwitchOnAsync(onEffect, offEffect, onWrite, timing, token);
        lock (_lock)
        {
            _cut.Burning(burn, burnIndex, on, _switching.BurstEndsAt);
        }

        _switching.LastWrite = Math.Max(onWrite, onWritten);
        WatchGate(on, onAnswered, "the laser gate did not acknowledge the switch-on");
        RunProgress progress;
        lock (_lock)
        {
            _accounting.Current(burn, burnIndex);
            _progress = Snapshot();
            progress = _progress;
        }

        ProgressChanged?.Invoke(this, progress);
        await EndBurnRunAsync(s, k, burn, offWrite, offEffect, token);

        // A run counts as burned once its switch-on is acknowledged (a silent gate burns nothing).
        _completions.UpTo(stroke, burnIndex, on);

        if (s.Bumps.TryGetValue(stroke.Distance(burn.X1), out var bump))
        {
            s.Flown = (bump, await _position.FlyGapAsync(bump, times.Arrival + s.Shift, timing, token));
        }
    }

    /// <summary>The end of burn run <paramref name="k"/>: its switch-off at its time, or left to the burst's count when a line would not fit.</summary>
    private async Task EndBurnRunAsync(StrokeUnderWay s, int k, Move burn, double offWrite, double offEffect, CancellationToken token)
    {
        var (stroke, timing) = (s.Stroke, s.Timing);

        // A scheduled switch-on is written well ahead: when the next one is due before this run's switch-off, the
        // switch-off is left out, since written after that line it would cancel the burst armed by it; the count
        // ends this run by itself.
        var nextWrite = k + 1 < stroke.RunCount && _switching.ScheduledBursts && !s.FlownAfter(burn.X1) ? s.NextScheduledWrite(stroke.RunAt(k + 1).Move, _switching.BurstEndsAt) : double.PositiveInfinity;
        var offLeftOut = offWrite + timing.OffWireSeconds > nextWrite;
        await KeepAlivesUntilAsync(Math.Min(offWrite, nextWrite), timing, token);
        if (offLeftOut)
        {
            _laser.MarkOff(Math.Max(0, offEffect - RunSeconds));
            NotBurning();
            return;
        }

        await DelayUntilAsync(offWrite, token);

        // A frequency-only gate fires until told otherwise: its switch-off is never left out.
        if (k + 1 < stroke.RunCount && _profile.Gate.CountsBursts && !s.FlownAfter(burn.X1) && !s.OffFitsBefore(stroke.RunAt(k + 1).Move, offEffect))
        {
            // A gap too short for the switch-off's line and the next burst's: the burst ends this run by itself.
            _laser.MarkOff(timing.OffLeadSeconds);
            NotBurning();
            return;
        }

        var (off, offWritten) = await _switching.SendSwitchOffAsync(timing);
        NotBurning();
        _switching.LastWrite = offWrite;
        WatchGate(off, Later(offWrite, offWritten) + timing.OffRoundTripSeconds, "the laser gate did not acknowledge the switch-off", switchOff: true);
        _switching.NoteSwitchOffLate(offWrite, offWritten, timing);

        void NotBurning()
        {
            lock (_lock)
            {
                _cut.NotBurning();
            }
        }
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

        _completions.Up(move, index, null);
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
            var next = Math.Max(_switching.LastWrite + period, RunSeconds);
            if (next + timing.KeepAliveRoundTripSeconds + (2 * timing.GateJitterSeconds) + 0.001 >= offWrite)
            {
                return;
            }

            await DelayUntilAsync(next, token);
            _switching.LastWrite = RunSeconds;
            _switching.KeepAliveWritten(_switching.LastWrite, timing);
            WatchGate(Gate.KeepAliveAsync(CancellationToken.None), _switching.LastWrite + timing.KeepAliveRoundTripSeconds, "the laser gate did not answer the keepalive");
        }
    }

    /// <summary>How much later than <paramref name="plannedWrite"/> (run seconds) a command's write completed; 0 when on time or unknown.</summary>
    private async Task<double> WrittenLateAsync(Task<long?> lineWritten, double plannedWrite) =>
        await lineWritten is { } stamp && TimeProvider.GetElapsedTime(_engravingStart, stamp).TotalSeconds - plannedWrite is > LateSeconds and var late ? late : 0;

    private static double Sent(double plannedArrival, double writtenSeconds, TimedSwitching timing) => GateSwitching.Sent(plannedArrival, writtenSeconds, timing);

    // The actual time when it is later than planned by more than the clock's rounding, else the planned one.
    private static double Later(double planned, double actual) => GateSwitching.Later(planned, actual);

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

    /// <summary>The stop point's cut pixel when a timed raster run was cut in the middle of a burn run (<see cref="StrokeCut.Cut"/>). Caller holds the lock.</summary>
    private RunStopPoint CutWithin(RunStopPoint stop) => _program switch
    {
        RasterProgram { Timing: { } timing, Plan: var plan } => _cut.Cut(stop, timing, plan, _laser.OffConfirmed, _profile.Gate.WatchdogMs, _stoppedAtKnownPosition ? _x : null, SwitchOnRefused),
        RasterProgram { Plan: var plan } => StepCut(stop, plan),
        _ => stop,
    };

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
