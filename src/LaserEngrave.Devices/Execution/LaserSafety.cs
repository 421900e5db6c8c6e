using System.Globalization;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Scheduling;

namespace LaserEngrave.Devices.Execution;

/// <summary>
/// The laser's safety during a run: every laser command under one lock, the keepalive, whether the laser is on and for how
/// long it was, and the off sequence on abort and fault (OFF, and when that is in doubt every path to off at once, the
/// stage stopped meanwhile), with which path the gate confirmed.
/// </summary>
/// <remarks>
/// Its state lock is taken last (under the engine's, never the other way round) and never held across a call out.
/// The off sequence itself is <see cref="LaserOff"/>'s; docs/execution.md ("Faults and resume", "The laser-off path") describes it.
/// </remarks>
internal sealed class LaserSafety : IAsyncDisposable
{
    private readonly ILaserGate _gate;
    private readonly TimeProvider _time;
    private readonly int _frequencyHz;
    private readonly int _watchdogMs;
    private readonly double _stallMarginMs;
    private readonly ILaserSafetyRun _run;
    private readonly Lock _lock = new();
    private bool _on;
    private long _onSince;
    private double _onSeconds;
    private bool _offConfirmed = true;
    private string? _offProblem;
    private LaserOffPath? _offBy;

    // A switch-off refused or not acknowledged in time: the laser may still fire, so every path to off is taken at once.
    private bool _switchOffFailed;
    private Task? _pendingOff;
    private double _latestAnswerSeconds;

    // Set under the laser lock when an off sequence (a fault's or an abort's) starts: no switch-on is marked on after it.
    private bool _offSequenceStarted;
    private readonly LaserOff _off;
    private bool _keepAliveWhileOn;

    /// <param name="frequencyHz">The pulse frequency a switch-on (<c>FREQ f</c>) sets.</param>
    /// <param name="watchdogMs">The gate's watchdog time the run set (named when the laser cannot be confirmed off).</param>
    /// <param name="stallMarginMs">How much later than its round trip a switch-off's acknowledgement may come before it is in doubt.</param>
    /// <param name="run">What the off sequence needs of the run it guards.</param>
    public LaserSafety(ILaserGate gate, TimeProvider time, int frequencyHz, int watchdogMs, double stallMarginMs, ILaserSafetyRun run)
    {
        _gate = gate;
        _time = time;
        _frequencyHz = frequencyHz;
        _watchdogMs = watchdogMs;
        _stallMarginMs = stallMarginMs;
        _run = run;
        _off = new LaserOff(gate, time);
    }

    /// <summary>A gate that never replies (a frequency-only profile's choice): its OFF counts as sent, never as confirmed.</summary>
    public bool GateNeverReplies { get => _off.GateNeverReplies; init => _off.GateNeverReplies = value; }

    /// <summary>
    /// Every laser command goes under this lock, and a switch-on checks for an abort inside it: so once an abort has sent
    /// its switch-off, no switch-on can follow it on the wire.
    /// </summary>
    public AsyncLock Lock { get; } = new();

    /// <summary>The keepalive, once the run has started it (<see cref="StartKeepAlive"/>).</summary>
    public GateKeepAlive? KeepAlive { get; private set; }

    /// <summary>Whether the laser is (or is about to be) on.</summary>
    public bool On
    {
        get
        {
            lock (_lock)
            {
                return _on;
            }
        }
    }

    /// <summary>How long the laser was on, s (a switch-off's lead counted to its effect).</summary>
    public double OnSeconds
    {
        get
        {
            lock (_lock)
            {
                return _onSeconds;
            }
        }
    }

    /// <summary>Whether the last switch-off of the off sequence was acknowledged (true until one is in doubt).</summary>
    public bool OffConfirmed
    {
        get
        {
            lock (_lock)
            {
                return _offConfirmed;
            }
        }
    }

    /// <summary>What the off sequence found, read at once: whether the laser is confirmed off, why not, and which path confirmed it.</summary>
    public (bool Confirmed, string? Problem, LaserOffPath? By) OffState
    {
        get
        {
            lock (_lock)
            {
                return (_offConfirmed, _offProblem, _offBy);
            }
        }
    }

    /// <summary>Starts feeding the gate's watchdog.</summary>
    /// <param name="whileOn">Whether the keepalive runs while the laser is on (step by step and dots); timed runs feed the watchdog in their own gate schedule.</param>
    /// <param name="failed">Called when the gate does not answer a keepalive.</param>
    public void StartKeepAlive(TimeSpan period, bool whileOn, Action<Exception> failed)
    {
        _keepAliveWhileOn = whileOn;
        KeepAlive = new GateKeepAlive(_gate, period, _time, failed);
    }

    /// <summary>Switches the laser on (<c>FREQ f</c>, unless an abort came first) or off (<c>OFF</c>), awaiting the gate's acknowledgement.</summary>
    /// <remarks>
    /// A switch-off not acknowledged within its round trip (<see cref="LaserOff.ConfirmWindow(TimedSwitching, double, double)"/>,
    /// the test a timed run's switch-offs get) is in doubt at once, not after the gate's whole timeout: every path to off
    /// goes out then (<see cref="LaserOff.EveryWayOffAsync"/>). Answered late after all, it confirms the laser off and the
    /// run goes on (the watchdog set back); refused or unanswered, it throws, the laser's state recorded for the fault.
    /// </remarks>
    public async Task SwitchAsync(bool on)
    {
        if (on)
        {
            await SwitchOnAsync();
            return;
        }

        await Lock.WaitAsync();
        try
        {
            if (KeepAlive is not null)
            {
                KeepAlive.Active = false;
            }

            Task off;
            var sent = _time.GetTimestamp();
            try
            {
                off = _gate.OffAsync(CancellationToken.None);
            }
            catch (Exception ex)
            {
                off = Task.FromException(ex);
            }

            // A plain timer, not PreciseDelay: this is a deadline the reply almost always beats, not a timed send, and
            // on the twin every PreciseDelay draws the loaded host's lateness, which would shift every later draw.
            var window = ConfirmWindow();
            using (var wait = new CancellationTokenSource())
            {
                var deadline = Task.Delay(window, _time, wait.Token);
                await Task.WhenAny(off, deadline);
                wait.Cancel();
            }

            if (!off.IsCompletedSuccessfully)
            {
                // In doubt: every path to off at once, now, the stage stopped with them (step by step it stands here).
                var refused = off.IsFaulted ? off.Exception?.InnerException : null;
                var result = await _off.EveryWayOffAsync(refused, off, _watchdogMs, _run.StopStageAsync);
                MarkOff();
                if (result.AllAnswered)
                {
                    // Only late (a loaded computer, a slow link): every command answered, the laser confirmed off, and step
                    // by step nothing depends on when; the watchdog the emergency shortened is set back and the run goes on.
                    // (A lost answer is not late: the replies to OFF and FREQ 0 read the same, so one goes unanswered.)
                    NoteAnswered(sent, _run.Timing.OffRoundTripSeconds);
                    await _gate.SetWatchdogAsync(_watchdogMs, CancellationToken.None);
                    return;
                }

                lock (_lock)
                {
                    _switchOffFailed = true;
                    _offBy = result.Path;
                    _offConfirmed = result.Confirmed;
                    _offProblem = result.Problem;
                }

                throw refused is not null
                    ? refused as DeviceException ?? new DeviceException($"the laser gate did not switch the laser off: {refused.Message}", refused)
                    : new DeviceException(string.Create(CultureInfo.InvariantCulture, $"the laser gate did not acknowledge the switch-off within {_stallMarginMs:0} ms of its expected arrival"));
            }

            NoteAnswered(sent, _run.Timing.OffRoundTripSeconds);
            MarkOff();
        }
        finally
        {
            Lock.Release();
        }
    }

    /// <summary>
    /// <c>FREQ f</c>, unless an abort came first: started under the laser lock, so that it is written before an abort's
    /// switch-off or not at all (the gate drops a command asked for before an emergency command), but its acknowledgement
    /// is awaited outside it, so that an abort's switch-off never waits behind a gate that does not answer.
    /// </summary>
    private async Task SwitchOnAsync()
    {
        Task ack;
        long sent;
        await Lock.WaitAsync();
        try
        {
            // Inside the lock: an abort's switch-off is either already sent (and we stop here) or comes after this.
            _run.ThrowIfAborted();

            // Gate commands are not cancelled: a reply arriving after a cancelled command would be taken for the next one's.
            sent = _time.GetTimestamp();
            ack = Start(() => _gate.SetFrequencyAsync(_frequencyHz, CancellationToken.None));
        }
        finally
        {
            Lock.Release();
        }

        await ack;
        NoteAnswered(sent, _run.Timing.FrequencyRoundTripSeconds(_frequencyHz));
        await Lock.WaitAsync();
        try
        {
            // An abort's off sequence ran while the acknowledgement was on its way: the laser is off, and stays so.
            _run.ThrowIfAborted();
            if (_offSequenceStarted)
            {
                throw new OperationCanceledException("the laser was switched off while its switch-on was answered");
            }

            MarkOn(_time.GetTimestamp());
            KeepAlive!.Active = _keepAliveWhileOn;
        }
        finally
        {
            Lock.Release();
        }
    }

    // A call that throws before it returns its task fails that task instead.
    private static Task Start(Func<Task> send)
    {
        try
        {
            return send();
        }
        catch (Exception ex)
        {
            return Task.FromException(ex);
        }
    }

    // How much later than its round trip a switching of this run was answered, at most: a computer or a link that late
    // (a loaded computer on real ports) answers a switch-off that late too.
    private void NoteAnswered(long sent, double roundTripSeconds)
    {
        var late = _time.GetElapsedTime(sent).TotalSeconds - roundTripSeconds;
        lock (_lock)
        {
            _latestAnswerSeconds = Math.Max(_latestAnswerSeconds, late);
        }
    }

    /// <summary>The laser is on from <paramref name="since"/> (a timestamp of the run's clock); the caller holds <see cref="Lock"/> and has sent the switch-on.</summary>
    public void MarkOn(long since)
    {
        lock (_lock)
        {
            _on = true;
            _onSince = since;
        }
    }

    /// <summary>The laser is off, <paramref name="leadSeconds"/> from now (a switch-off sent that takes effect later).</summary>
    public void MarkOff(double leadSeconds = 0)
    {
        lock (_lock)
        {
            if (_on)
            {
                _onSeconds += Math.Max(0, _time.GetElapsedTime(_onSince).TotalSeconds + leadSeconds);
                _on = false;
            }
        }
    }

    /// <summary>A counted burst has surely ended: the laser is off, and was on for the burst's length.</summary>
    public void MarkBurstOver(double burstSeconds)
    {
        lock (_lock)
        {
            _on = false;
            _onSeconds += burstSeconds;
        }
    }

    /// <summary>A switch-off was refused or not acknowledged: the fault's off sequence takes every path at once.</summary>
    /// <param name="pending">The OFF still waiting for its answer, when it is (a late answer confirms the laser off too).</param>
    public void MarkSwitchOffFailed(Task? pending = null)
    {
        lock (_lock)
        {
            _switchOffFailed = true;
            _pendingOff = pending ?? _pendingOff;
        }
    }

    // How long a switch-off may take to be acknowledged now: the timed path's test, behind whatever is on the gate's wire,
    // and as much later again as this run's switchings have been answered late at most.
    private TimeSpan ConfirmWindow()
    {
        double late;
        lock (_lock)
        {
            late = _latestAnswerSeconds;
        }

        return LaserOff.ConfirmWindow(_run.Timing, _stallMarginMs, _run.GateQueueSeconds + late);
    }

    /// <summary>
    /// Switches the laser off after a fault or an abort: OFF, and when that (or an earlier switch-off) was refused or went
    /// unanswered, every other path at once (<see cref="EveryWayOffAsync"/>); records which one the gate confirmed.
    /// </summary>
    public async Task OffSafelyAsync()
    {
        await Lock.WaitAsync();
        try
        {
            if (KeepAlive is not null)
            {
                KeepAlive.Active = false;
            }

            bool everyPathTaken, inDoubt;
            lock (_lock)
            {
                // Every path was taken once already: the laser is confirmed off, or its port is closed and a person must check it.
                everyPathTaken = _offBy is LaserOffPath.OffAgain or LaserOffPath.FrequencyZero or LaserOffPath.None;
                inDoubt = _switchOffFailed;
            }

            _offSequenceStarted = true;
            _run.OffSequenceStarting(everyPathTaken ? null : inDoubt);
            if (everyPathTaken)
            {
                return;
            }

            Task? pending;
            lock (_lock)
            {
                pending = _pendingOff;
            }

            var result = inDoubt
                ? await _off.EveryWayOffAsync(null, pending, _watchdogMs, _run.StopStageAsync)
                : await _off.SwitchOffAsync(ConfirmWindow(), _watchdogMs, _run.StopStageAsync);
            MarkOff();
            lock (_lock)
            {
                _offBy = result.Path;
                _offConfirmed = result.Confirmed;
                _offProblem = result.Problem;
            }
        }
        finally
        {
            Lock.Release();
        }
    }

    public async ValueTask DisposeAsync()
    {
        if (KeepAlive is not null)
        {
            await KeepAlive.DisposeAsync();
        }
    }
}

/// <summary>What <see cref="LaserSafety"/> needs of the run it guards.</summary>
internal interface ILaserSafetyRun
{
    /// <summary>The gate's timing: the run's own, or for a run without one (step by step, dots) the process' on this machine.</summary>
    TimedSwitching Timing { get; }

    /// <summary>
    /// How much later than its own round trip a line written to the gate now is answered: the lines and the replies still
    /// ahead of it on the gate's wire (a timed switch-on just written, its reply); 0 when nothing is.
    /// </summary>
    double GateQueueSeconds { get; }

    /// <summary>Throws when an abort was asked (checked inside the laser lock before a switch-on).</summary>
    void ThrowIfAborted();

    /// <summary>An off sequence (a fault's or an abort's) starts, under the laser lock.</summary>
    /// <param name="inDoubt">Whether an earlier switch-off was refused or unanswered; null when every path to off was taken already (nothing more is sent).</param>
    void OffSequenceStarting(bool? inDoubt);

    /// <summary>Stops both axes (sent while the gate's paths to off are in doubt, so nothing more is swept).</summary>
    Task StopStageAsync();
}
