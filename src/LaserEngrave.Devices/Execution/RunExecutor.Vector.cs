using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Zaber;

namespace LaserEngrave.Devices.Execution;

/// <summary>Vector jobs: each step of a drawing's <see cref="DrawingProgram"/> sent by time, both axes streaming their speeds, the laser switched by time.</summary>
/// <remarks>
/// Every command leaves so that it arrives when the schedule says (the adapter's latency and a frame ahead). Before the
/// laser comes on, the stroke's position query must show the stage where the model has it, give or take the latencies;
/// every reply is watched against its expected arrival, and one missing or late ends the run, laser off first. Between
/// strokes the laser is off and acknowledged, the axes rest, and a travel takes them to the next run-up's start
/// (its replies awaited, so every stroke starts from a known position). Pauses come between strokes.
/// </remarks>
public sealed partial class RunExecutor
{
    // Time the host allows itself to react to a reply before acting on it (as TimedSwitching).
    private const double VectorReactionSeconds = 0.0005;

    /// <summary>A drawing's motion from the first stroke to run (a resumed run's stop point), with the estimates of what was done before.</summary>
    private Func<CancellationToken, Task> PrepareStrokes(DrawingProgram program)
    {
        var first = 0;
        if (Options.ResumeFrom is { } resume)
        {
            if (resume.MoveIndex < 0 || resume.MoveIndex > program.StrokeCount)
            {
                throw new PreflightException($"the resume point (stroke {resume.MoveIndex}) is not in this drawing's {program.StrokeCount} strokes");
            }

            first = (int)resume.MoveIndex;
            _accounting.DoneBefore(first, program.Steps().Take(first).Count(s => s.LastOfPath));
        }

        _accounting.EstimateTotal = Part.EngravingSeconds;
        _accounting.EstimateBefore = Part.EngravingSeconds - program.SecondsFrom(first);

        // Preflight, homing if it homes, and the travel to the first stroke's run-up, as for images (TimedSwitching.PreparationSeconds).
        _accounting.EstimatePreparation = program.Steps(first).Take(1).ToList() is [var step]
            ? program.Timing.PreparationSeconds(step.Travel.To.X, step.Travel.To.Y, _homed, from: (_x, _y))
            : 0;
        return token => ExecuteVectorAsync(program, first, token);
    }

    private async Task ExecuteVectorAsync(DrawingProgram program, int first, CancellationToken token)
    {
        var timing = program.Timing;
        await BeginEngravingAsync(first, first, token);
        var travelWrite = double.NaN;
        foreach (var step in program.Steps(first))
        {
            var k = step.Index;
            var travel = step.Travel;
            _accounting.At(k, k);

            if (travel.From is null)
            {
                // Reaching the first run-up (the plan's or the resume point's) is not part of the estimate.
                var positioning = TimeProvider.GetTimestamp();
                await MoveToAsync(travel.To.X, travel.To.Y, travel.SpeedData, token);
                _notEngraving += TimeProvider.GetElapsedTime(positioning);
            }
            else
            {
                await DelayUntilAsync(travelWrite, token);
                if (IsPauseRequested)
                {
                    // Pauses come between strokes, with the laser off and the stage at rest.
                    await PauseIfAskedAsync(token);
                }

                // Where a streamed axis rests depends on when each of its commands arrived (the latencies' spread), not on
                // the model alone: it is moved to the run-up's start even when the model has it there already, so the
                // stroke starts from a position the stage has reported (skipped, the spread added up stroke after stroke).
                await MoveToAsync(travel.To.X, travel.To.Y, travel.SpeedData, token, (travel.StreamedX, travel.StreamedY));
            }

            await DelayUntilAsync(RunSeconds + VectorReactionSeconds, token);
            travelWrite = await VectorStrokeAsync(step.Stroke, timing, token);
            StrokeDone(step);
        }

        await DelayUntilAsync(travelWrite, token);
        _accounting.At(program.StrokeCount, program.StrokeCount);
    }

    /// <summary>One stroke by time; returns when (run seconds) the travel to the next stroke may be written.</summary>
    private async Task<double> VectorStrokeAsync(VectorStroke stroke, TimedSwitching timing, CancellationToken token)
    {
        var write = RunSeconds;
        var origin = write + timing.StageCommandSeconds;
        var onWrite = timing.BurstWriteSeconds(origin + stroke.LaserOnSeconds, origin + stroke.LaserOffSeconds);
        var offWrite = origin + stroke.LaserOffSeconds - timing.OffLeadSeconds;
        var events = new List<(double Write, int Order, Func<Task> Send)>();
        var due = new List<(Task Reply, double Due, string What, ReplyWatch.Watched Watched)>();
        var sent = new VectorStrokeSent();
        AddAxisCommands(events, due, sent, stroke, timing, origin, token);
        AddGateCommands(events, sent, stroke, timing, origin, onWrite, offWrite, token);
        foreach (var (at, _, send) in events.OrderBy(e => e.Write).ThenBy(e => e.Order))
        {
            await DelayUntilAsync(at, token);
            ThrowIfAborted();

            // Every reply that is due is looked at before each command: a stage that stops answering (or acting) is
            // caught within a slot of its reply's deadline, on the stroke's own path, not by a watcher's timer.
            CheckDue(due);
            await send();
        }

        // The travel leaves once the axes rest and the switch-off is acknowledged.
        var travel = write + stroke.NextArrivalSeconds;
        if (!await CompletesByAsync(sent.Off!, travel, token) || !sent.Off!.IsCompletedSuccessfully)
        {
            _laser.MarkSwitchOffFailed();
            throw Fault("the laser gate had not acknowledged the switch-off when the stage was to travel");
        }

        _laser.MarkOff();
        lock (_lock)
        {
            _x = stroke.RestEnd.X;
            _y = stroke.RestEnd.Y;
        }

        return travel;
    }

    /// <summary>What a stroke's commands have sent so far: its position query (and of which axis), its switch-off.</summary>
    private sealed class VectorStrokeSent
    {
        public Task<long>? Poll { get; set; }

        public IStageAxis? Polled { get; set; }

        public Task? Off { get; set; }
    }

    /// <summary>Each axis command of the stroke (speed, stop, position query) at its time, its reply watched.</summary>
    private void AddAxisCommands(List<(double Write, int Order, Func<Task> Send)> events, List<(Task Reply, double Due, string What, ReplyWatch.Watched Watched)> due, VectorStrokeSent sent, VectorStroke stroke, TimedSwitching timing, double origin, CancellationToken token)
    {
        var stall = (2 * timing.StageJitterSeconds) + Units.MsToSeconds(Options.StallMarginMs);
        foreach (var command in stroke.Commands)
        {
            var axis = command.Axis == VectorAxis.X ? Stage.X : Stage.Y;
            var name = command.Axis.ToString();
            var arrival = origin + command.AtSeconds;
            events.Add((arrival - timing.StageCommandSeconds, 0, () =>
            {
                switch (command.Kind)
                {
                    case AxisCommandKind.Speed:
                        var speed = Settled(axis.StreamSpeedAsync(command.SpeedData, token));
                        var watched = Watch(speed, arrival + timing.StageReplySeconds, $"a speed change of its stroke ({name})");
                        due.Add((speed, arrival + timing.StageReplySeconds + stall, $"a speed change of its stroke ({name})", watched));
                        break;
                    case AxisCommandKind.Stop:
                        Watch(Settled(axis.StreamStopAsync(token)), arrival + (timing.BurnSpeed / timing.Acceleration) + timing.StageReplySeconds, $"the stop of its stroke ({name})");
                        break;
                    default:
                        sent.Poll = axis.GetPositionAsync(token);
                        sent.Polled = axis;
                        break;
                }

                return Task.CompletedTask;
            }));
        }
    }

    /// <summary>The stroke's switch-on once its position is confirmed, the keepalives while it burns, its switch-off.</summary>
    private void AddGateCommands(List<(double Write, int Order, Func<Task> Send)> events, VectorStrokeSent sent, VectorStroke stroke, TimedSwitching timing, double origin, double onWrite, double offWrite, CancellationToken token)
    {
        events.Add((onWrite, 1, async () =>
        {
            await ConfirmStrokeAsync(sent.Poll, sent.Polled, stroke, timing, onWrite, token);
            await DelayUntilAsync(onWrite, token);
            var (on, onWritten) = await _switching.SendSwitchOnAsync(origin + stroke.LaserOnSeconds, origin + stroke.LaserOffSeconds, timing);
            _switching.LastWrite = onWrite;
            WatchGate(on, Later(onWrite, onWritten) + timing.OnRoundTripSeconds, "the laser gate did not acknowledge the switch-on");
        }));

        var period = GateKeepAlive.PeriodFor(_profile.Gate.WatchdogMs, Options.KeepAliveFraction).TotalSeconds;
        for (var ping = onWrite + period; period > 0 && ping + timing.KeepAliveRoundTripSeconds + (2 * timing.GateJitterSeconds) + 0.001 < offWrite; ping += period)
        {
            var at = ping;
            events.Add((at, 2, () =>
            {
                _switching.LastWrite = at;
                _switching.KeepAliveWritten(RunSeconds, timing);
                WatchGate(Gate.KeepAliveAsync(CancellationToken.None), at + timing.KeepAliveRoundTripSeconds, "the laser gate did not answer the keepalive");
                return Task.CompletedTask;
            }));
        }

        events.Add((offWrite, 3, async () =>
        {
            (sent.Off, var offWritten) = await _switching.SendSwitchOffAsync(timing);
            _switching.LastWrite = offWrite;
            WatchGate(sent.Off, Later(offWrite, offWritten) + timing.OffRoundTripSeconds, "the laser gate did not acknowledge the switch-off", switchOff: true);
            _switching.NoteSwitchOffLate(offWrite, offWritten, timing);
        }));
    }

    private void CheckDue(List<(Task Reply, double Due, string What, ReplyWatch.Watched Watched)> due)
    {
        var now = RunSeconds;
        for (var i = due.Count - 1; i >= 0; i--)
        {
            var (reply, at, what, watched) = due[i];
            if (reply.IsCompletedSuccessfully)
            {
                due.RemoveAt(i);
            }
            else if (reply.IsFaulted && reply.Exception?.InnerException is DeviceException refused)
            {
                throw Fault(refused.Message);
            }
            else if (Math.Max(at, watched.Deadline) < now && !Stage.IsReceiving && !watched.StillWriting)
            {
                // Written late or bytes still arriving (a stalled computer): its watch decides, the deadline moved by the
                // late write, with the grace it gives.
                throw Fault($"the stage did not report {what} within {Options.StallMarginMs:0} ms of its expected arrival (stalled, or its reply was lost)");
            }
        }
    }

    /// <summary>Before the switch-on: the position query shows the stroke's axis where the model has it, give or take both latencies.</summary>
    private async Task ConfirmStrokeAsync(Task<long>? poll, IStageAxis? axis, VectorStroke stroke, TimedSwitching timing, double onWrite, CancellationToken token)
    {
        var name = axis == Stage.Y ? "Y" : "X";
        if (poll is null || !await CompletesByAsync(poll, onWrite, token))
        {
            throw Fault($"the {name} axis did not answer the position query before the laser was to come on", recoverable: true);
        }

        long position;
        try
        {
            position = await poll;
        }
        catch (DeviceException ex)
        {
            throw Fault($"the {name} axis did not answer the position query before the laser was to come on: {ex.Message}");
        }

        var start = name == "X" ? stroke.RunUpStart.X : stroke.RunUpStart.Y;
        var tolerance = Math.Ceiling(timing.BurnSpeed * 4 * timing.StageJitterSeconds) + 2;
        var direction = Math.Sign(stroke.QueryExpected - start);
        var moved = (position - start) * direction;
        if (Math.Abs(position - stroke.QueryExpected) > tolerance || moved < 1)
        {
            throw Fault($"the {name} axis reported {position} microsteps just after starting its stroke, not {stroke.QueryExpected} ± {tolerance}: it is not moving as planned, so the laser stays off");
        }
    }

    private void StrokeDone(DrawingStep step)
    {
        var stroke = step.Stroke;
        RunProgress progress;
        lock (_lock)
        {
            _accounting.StrokeDone(stroke.Index, step.LastOfPath);
            _progress = Snapshot();
            progress = _progress;
        }

        var points = stroke.Path.Points;
        for (var i = 1; i < points.Count; i++)
        {
            MoveCompleted?.Invoke(this, new MoveCompletedEventArgs(new Move(MoveKind.Burn, points[i - 1].X, points[i - 1].Y, points[i].X, points[i].Y, stroke.Index), stroke.Index));
        }

        ProgressChanged?.Invoke(this, progress);
    }

    /// <summary>
    /// A stroke's command settled: acknowledged, or counted as replaced when the stroke's stop has reported its end
    /// (a lost reply to a speed change the axis has carried out, as its later replies show).
    /// </summary>
    private static async Task Settled<T>(Task<T> reply)
    {
        try
        {
            await reply;
        }
        catch (ZaberInterruptedException)
        {
            // Only the stop at the stroke's end replaces earlier commands (each speed change waits for its own reply).
        }
    }
}
