using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Zaber;
using LaserEngrave.Wire.Scheduling;

namespace LaserEngrave.Devices.Execution;

/// <summary>
/// The replies a timed run does not wait for, each watched against its expected arrival: one missing, late, failed or
/// wrong is reported to the run as its fault (which turns the laser off first). A move of an axis is settled by the next
/// move of that axis when its own end is never reported.
/// </summary>
/// <remarks>
/// Used from the run's loop only (its watchers run on the run's task runner and read an entry's deadline and successor);
/// times are seconds on the run's clock (<see cref="IReplyWatchRun.RunSeconds"/>). docs/execution.md describes the deadlines.
/// </remarks>
internal sealed class ReplyWatch
{
    private readonly TimeProvider _time;
    private readonly double _stallMarginMs;
    private readonly IReplyWatchRun _run;
    private readonly List<Watched> _watched = [];
    private readonly Dictionary<string, Watched> _lastMove = [];

    /// <param name="stallMarginMs">How much later than its expected arrival (and twice the jitter) a reply may come.</param>
    /// <param name="run">What the watch needs of the run: its clock, its timing, and where its faults go.</param>
    public ReplyWatch(TimeProvider time, double stallMarginMs, IReplyWatchRun run)
    {
        _time = time;
        _stallMarginMs = stallMarginMs;
        _run = run;
    }

    /// <summary>How often a reply whose time is up is looked for again while bytes are still arriving (the gate's waits' recheck).</summary>
    internal static readonly TimeSpan ArrivingRecheck = TimeSpan.FromMilliseconds(5);

    /// <summary>
    /// How long past its deadline a reply may still be looked for while bytes are still arriving on its link: a host that
    /// stalled (another process, a page fault) reads a reply that came in time 20-100 ms late, and that is not the
    /// device stalling. Nothing arriving, the deadline stands.
    /// </summary>
    internal static readonly TimeSpan ArrivingGrace = TimeSpan.FromMilliseconds(250);

    /// <summary>Whether bytes are still arriving on the gate's link (true) or the stage's (false); null: never (the deadline stands).</summary>
    public Func<bool, bool>? Arriving { get; init; }

    /// <summary>
    /// When the command asked for last on the gate's link (true) or the stage's (false) was written (its write's completion,
    /// a timestamp of the run's clock; null: unknown); null: the watch does not ask. A watched reply's deadline moves later
    /// by however much later its command's write completed than the watch began: a computer that stalled before the
    /// write sent the command late, and its reply comes that much later, stage and gate alike.
    /// </summary>
    public Func<bool, Task<long?>>? Written { get; init; }

    /// <summary>Watches a reply: late past its expected arrival (plus the stall margin), failed or wrong, it ends the run, laser off first.</summary>
    /// <remarks>
    /// A move of an axis (<paramref name="axis"/>) is sent to arrive just after the one before has ended; should it catch
    /// that one in its last moments, the device may never report the earlier end (the protocol leaves it open). So an
    /// earlier move whose reply is missing or says it was replaced counts as done once the later move reports its end.
    /// </remarks>
    /// <param name="switchOff">A switch-off: refused or unanswered, the laser may still fire, so the fault takes every path to off.</param>
    /// <returns>The watched reply, whose deadline a stroke found behind its plan may move later.</returns>
    public Watched Watch(Task reply, double expectedSeconds, string what, bool gate = false, string? axis = null, bool switchOff = false)
    {
        var jitter = gate ? _run.Timing?.GateJitterSeconds : _run.Timing?.StageJitterSeconds;
        var deadline = expectedSeconds + ((jitter ?? 0) * 2) + Units.MsToSeconds(_stallMarginMs);
        var watched = new Watched(reply, deadline, what) { SwitchOff = switchOff, Gate = gate };
        if (axis is not null)
        {
            if (_lastMove.TryGetValue(axis, out var before))
            {
                before.Successor = watched;
            }

            _lastMove[axis] = watched;
        }

        _watched.Add(watched);
        var written = Written?.Invoke(gate) is { IsCompleted: false } stillWriting ? stillWriting : null;
        watched.Written = written;
        var asked = _time.GetTimestamp();
        _ = TaskRunner.For(_time).Start(() => WatchAsync(watched, gate, written, asked));
        return watched;
    }

    /// <summary>The replies watched and not yet settled; settled ones need no more looking at (their watchers report any fault), so the list stays short.</summary>
    public IReadOnlyList<Watched> Unsettled()
    {
        _watched.RemoveAll(w => w.Reply.IsCompletedSuccessfully || (w.Successor?.Reply.IsCompletedSuccessfully ?? false));
        return _watched.ToList();
    }

    /// <summary>Waits for every reply watched so far, each by its deadline (a move never reported is settled by the next of its axis); one missing faults the run.</summary>
    public async Task AllSettledAsync(CancellationToken token)
    {
        foreach (var watched in _watched.ToList())
        {
            var deadline = watched.Successor is { } later ? Math.Max(watched.Deadline, later.Deadline) : watched.Deadline;
            var settled = watched.Settled();
            if (!await CompletesByAsync(settled, deadline + 0.001, token) && !await StillArrivingAsync(settled, watched.Gate, token))
            {
                throw _run.Fault(
                    $"the stage did not report {watched.What} within {_stallMarginMs:0} ms of its expected arrival (stalled, or its reply was lost)",
                    recoverable: !watched.Gate);
            }
        }
    }

    /// <summary>Forgets every reply watched (all settled).</summary>
    public void Clear() => _watched.Clear();

    /// <summary>Whether <paramref name="task"/> has completed by <paramref name="seconds"/> on the run's clock (waiting until then at most).</summary>
    public async Task<bool> CompletesByAsync(Task task, double seconds, CancellationToken token)
    {
        token.ThrowIfCancellationRequested();
        var wait = seconds - _run.RunSeconds;
        if (task.IsCompleted || wait <= 0)
        {
            return task.IsCompleted;
        }

        using var stop = CancellationTokenSource.CreateLinkedTokenSource(token);
        var timer = PreciseDelay.DelayAsync(_time, TimeSpan.FromSeconds(wait), stop.Token);
        await Task.WhenAny(task, timer);
        stop.Cancel();
        token.ThrowIfCancellationRequested();
        return task.IsCompleted;
    }

    /// <summary>
    /// After a deadline passed: while bytes are still arriving on the reply's link, looks again every few milliseconds
    /// (at most <see cref="ArrivingGrace"/>); returns whether the reply came meanwhile.
    /// </summary>
    private async Task<bool> StillArrivingAsync(Task reply, bool gate, CancellationToken token)
    {
        if (Arriving is not { } arriving)
        {
            return reply.IsCompleted;
        }

        // A plain timer, not PreciseDelay: a recheck is not a timed send, and on the twin every PreciseDelay draws the
        // loaded host's lateness, which would shift every later draw.
        var until = _time.GetTimestamp() + (long)(ArrivingGrace.TotalSeconds * _time.TimestampFrequency);
        while (!reply.IsCompleted && _time.GetTimestamp() < until && arriving(gate))
        {
            using var stop = CancellationTokenSource.CreateLinkedTokenSource(token);
            await Task.WhenAny(reply, Task.Delay(ArrivingRecheck, _time, stop.Token));
            stop.Cancel();
            token.ThrowIfCancellationRequested();
        }

        return reply.IsCompleted;
    }

    private async Task WatchAsync(Watched watched, bool gate, Task<long?>? written, long asked)
    {
        try
        {
            var reply = watched.Reply;
            if (written is not null && await written is { } stamp && _time.GetElapsedTime(asked, stamp) is { Ticks: > 0 } late)
            {
                // Written late (a stalled computer): the reply is expected that much later.
                watched.Deadline += late.TotalSeconds;
            }

            // Waits again when the deadline moved later meanwhile (a stroke found behind its plan), never for the same one twice.
            for (var deadline = double.NegativeInfinity; watched.Deadline > deadline && !reply.IsCompleted;)
            {
                deadline = watched.Deadline;
                var wait = deadline - _run.RunSeconds;
                if (wait <= 0)
                {
                    break;
                }

                using var stop = new CancellationTokenSource();
                await Task.WhenAny(reply, PreciseDelay.DelayAsync(_time, TimeSpan.FromSeconds(wait), stop.Token));
                stop.Cancel();
            }

            await StillArrivingAsync(reply, gate, CancellationToken.None);
            if (reply.IsCompletedSuccessfully)
            {
                return;
            }

            if (watched.Successor is { } successor && (!reply.IsCompleted || reply.Exception?.InnerException is ZaberInterruptedException))
            {
                await successor.Done.Task;
                return;
            }

            if (watched.SwitchOff)
            {
                _run.SwitchOffFailed(reply);
            }

            if (!reply.IsCompleted)
            {
                // A stage reply missing past its grace is a doubt about time, not about the laser: the run stops with the
                // laser off, and the session goes on from the stop point only if the off was confirmed and no burn run was
                // cut; a device that is gone fails the recovery's own checks. A gate's reply missing leaves the laser in doubt.
                _ = _run.Fault(
                    gate
                        ? $"{watched.What} within {_stallMarginMs:0} ms of its expected arrival"
                        : $"the stage did not report {watched.What} within {_stallMarginMs:0} ms of its expected arrival (stalled, or its reply was lost)",
                    recoverable: !gate);
                return;
            }

            await reply;
        }
        catch (OperationCanceledException)
        {
            // The run is ending anyway.
        }
        catch (Exception ex) when (ex is DeviceException)
        {
            _ = _run.Fault(ex.Message);
        }
        finally
        {
            watched.Done.TrySetResult();
        }
    }

    /// <summary>A reply being watched; <see cref="Done"/> completes once it is settled (or has faulted the run).</summary>
    internal sealed class Watched(Task reply, double deadline, string what)
    {
        public Task Reply { get; } = reply;

        /// <summary>When the reply is due at the latest (s on the run's clock); a stroke found behind its plan moves it later.</summary>
        public double Deadline { get; set; } = deadline;

        public string What { get; } = what;

        /// <summary>A switch-off: refused or unanswered, the fault's off sequence takes every path at once.</summary>
        public bool SwitchOff { get; init; }

        /// <summary>A reply of the gate (else of the stage): which link's arriving bytes may still be it.</summary>
        public bool Gate { get; init; }

        /// <summary>Its command's write, when it was still being written as the watch began (a stalled computer); null: written.</summary>
        public Task<long?>? Written { get; set; }

        /// <summary>True while its command is still being written: its deadline is not known yet (it moves with the write).</summary>
        public bool StillWriting => Written is { IsCompleted: false };

        /// <summary>The next move of the same axis, which settles this one if this one's end is never reported.</summary>
        public Watched? Successor { get; set; }

        public TaskCompletionSource Done { get; } = new(TaskCreationOptions.RunContinuationsAsynchronously);

        /// <summary>Completes once the reply came, or the next move of its axis (as it stands now) reported its own.</summary>
        public Task Settled() => Successor is { } next ? Task.WhenAny(Reply, next.Reply) : Reply;
    }
}

/// <summary>What a <see cref="ReplyWatch"/> needs of the run whose replies it watches.</summary>
internal interface IReplyWatchRun
{
    /// <summary>The run's clock, s since its engraving started.</summary>
    double RunSeconds { get; }

    /// <summary>The timing the run times itself with (the stage's and the gate's jitter), or null for a plan without one.</summary>
    TimedSwitching? Timing { get; }

    /// <summary>A reply missing, late, failed or wrong: the run's fault (the laser off at once); returns the exception to throw.</summary>
    /// <param name="reason">The fault, one line.</param>
    /// <param name="recoverable">A stage reply that did not come in time, nothing more: a timing doubt the session may go on from (<see cref="RunResult.Recoverable"/>).</param>
    DeviceException Fault(string reason, bool recoverable = false);

    /// <summary>A switch-off refused or unanswered: the laser may still fire, so the fault's off sequence takes every path.</summary>
    /// <param name="reply">The switch-off's acknowledgement, still awaited when it was late (a late answer confirms the laser off).</param>
    void SwitchOffFailed(Task reply);
}
