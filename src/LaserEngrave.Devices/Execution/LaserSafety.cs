using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Scheduling;
using LaserEngrave.Wire.Scheduling;

namespace LaserEngrave.Devices.Execution;

/// <summary>
/// The laser's safety during a run: every laser command under one lock, the keepalive, whether the laser is on and for how
/// long it was, and the off sequence on abort and fault (OFF, and when that is in doubt every path to off at once, the
/// stage stopped meanwhile), with which path the gate confirmed.
/// </summary>
/// <remarks>
/// Its state lock is taken last (under the engine's, never the other way round) and never held across a call out.
/// docs/execution.md ("Safety") describes the off sequence.
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
    }

    /// <summary>A gate that never replies (a frequency-only profile's choice): its OFF counts as sent, never as confirmed.</summary>
    public bool GateNeverReplies { get; init; }

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
    public async Task SwitchAsync(bool on)
    {
        await Lock.WaitAsync();
        try
        {
            if (on)
            {
                // Inside the lock: an abort's switch-off is either already sent (and we stop here) or comes after this.
                _run.ThrowIfAborted();

                // Gate commands are not cancelled: a reply arriving after a cancelled command would be taken for the next one's.
                await _gate.SetFrequencyAsync(_frequencyHz, CancellationToken.None);
                MarkOn(_time.GetTimestamp());
                KeepAlive!.Active = _keepAliveWhileOn;
            }
            else
            {
                if (KeepAlive is not null)
                {
                    KeepAlive.Active = false;
                }

                try
                {
                    await _gate.OffAsync(CancellationToken.None);
                }
                catch (DeviceException)
                {
                    MarkSwitchOffFailed();
                    throw;
                }

                MarkOff();
            }
        }
        finally
        {
            Lock.Release();
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
    public void MarkSwitchOffFailed()
    {
        lock (_lock)
        {
            _switchOffFailed = true;
        }
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

            _run.OffSequenceStarting(everyPathTaken ? null : inDoubt);
            if (everyPathTaken)
            {
                return;
            }

            DeviceException? refused = null;
            Task? first = null;
            if (!inDoubt)
            {
                first = _gate.OffAsync(CancellationToken.None);

                // Answered within its round trip (and the margin a stage reply gets), or it is in doubt: a gate gone deaf
                // must not leave the stage sweeping for the whole of the gate's timeout with the laser on.
                var timing = _run.Timing;
                var roundTrip = (timing?.OffRoundTripSeconds ?? 0.02) + (2 * (timing?.GateJitterSeconds ?? 0)) + Units.MsToSeconds(_stallMarginMs);
                using (var wait = new CancellationTokenSource())
                {
                    await Task.WhenAny(first, PreciseDelay.DelayAsync(_time, TimeSpan.FromSeconds(roundTrip), wait.Token));
                    wait.Cancel();
                }

                if (first.IsCompletedSuccessfully)
                {
                    MarkOff();
                    lock (_lock)
                    {
                        // A gate that never replies was sent OFF, and nothing says it heard it.
                        _offConfirmed = !GateNeverReplies;
                        _offProblem = GateNeverReplies
                            ? "the laser could not be confirmed off: OFF was sent, but this laser gate never replies; a person must check the laser"
                            : null;
                        _offBy = LaserOffPath.Off;
                    }

                    return;
                }

                refused = first.Exception?.InnerException as DeviceException;
            }

            await EveryWayOffAsync(refused, first);
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

    private static async Task Settled(Task task)
    {
        try
        {
            await task;
        }
        catch (DeviceException)
        {
            // Looked at through the task itself.
        }
    }

    /// <summary>
    /// A switch-off was refused or went unanswered: OFF again, FREQ 0 and the gate's shortest watchdog go out together,
    /// with a stop to both axes so that nothing more is swept; the first the gate acknowledges of OFF and FREQ 0 confirms
    /// the laser off. When neither is acknowledged the gate's port is closed, so that the gate hears nothing more and its
    /// watchdog switches the laser off, and the run says a person must check the laser. Caller holds the laser lock.
    /// </summary>
    /// <param name="refused">Why the switch-off was refused, when it was.</param>
    /// <param name="first">The fault's own OFF, still waiting for its answer (a late answer confirms the laser off too).</param>
    private async Task EveryWayOffAsync(DeviceException? refused, Task? first)
    {
        // Gate commands are not cancelled (a late reply would be taken for the next one's): each waits its own timeout.
        var off = _gate.OffAsync(CancellationToken.None);
        var zero = _gate.SetFrequencyAsync(0, CancellationToken.None);
        // A gate without a watchdog (frequency-only) has none to shorten.
        var watchdog = _watchdogMs > 0 ? _gate.SetWatchdogAsync(MachineProfileValidator.MinWatchdogMs, CancellationToken.None) : Task.FromException(new DeviceException("no watchdog"));
        var stopping = _run.StopStageAsync();
        await Task.WhenAll(Settled(first ?? Task.CompletedTask), Settled(off), Settled(zero), Settled(watchdog), stopping);
        var path = off.IsCompletedSuccessfully || first?.IsCompletedSuccessfully == true ? LaserOffPath.OffAgain
            : zero.IsCompletedSuccessfully ? LaserOffPath.FrequencyZero
            : LaserOffPath.None;
        MarkOff();
        if (path == LaserOffPath.None && _gate is IAsyncDisposable port)
        {
            // Silence on its line is the one thing left that switches the laser off: the gate's own watchdog.
            await port.DisposeAsync();
        }

        lock (_lock)
        {
            _offBy = path;
            _offConfirmed = path != LaserOffPath.None && !GateNeverReplies;
            var why = (refused ?? off.Exception?.InnerException ?? zero.Exception?.InnerException)?.Message;
            _offProblem = path != LaserOffPath.None
                ? (GateNeverReplies ? "the laser could not be confirmed off: OFF and FREQ 0 were sent, but this laser gate never replies; a person must check the laser" : null)
                : _watchdogMs <= 0
                ? $"the laser could not be confirmed off: the gate acknowledged neither OFF nor FREQ 0 ({why}), and it has no watchdog; a person must switch the laser off at its key now"
                : string.Create(
                    CultureInfo.InvariantCulture,
                    $"the laser could not be confirmed off: the gate acknowledged neither OFF nor FREQ 0 ({why}); its port was closed so that its watchdog ({(watchdog.IsCompletedSuccessfully ? MachineProfileValidator.MinWatchdogMs : _watchdogMs)} ms) switches the laser off; a person must check the laser");
        }
    }
}

/// <summary>What <see cref="LaserSafety"/> needs of the run it guards.</summary>
internal interface ILaserSafetyRun
{
    /// <summary>The timing the run times itself with (the switch-off's round trip), or null for a plan without one.</summary>
    TimedSwitching? Timing { get; }

    /// <summary>Throws when an abort was asked (checked inside the laser lock before a switch-on).</summary>
    void ThrowIfAborted();

    /// <summary>An off sequence (a fault's or an abort's) starts, under the laser lock.</summary>
    /// <param name="inDoubt">Whether an earlier switch-off was refused or unanswered; null when every path to off was taken already (nothing more is sent).</param>
    void OffSequenceStarting(bool? inDoubt);

    /// <summary>Stops both axes (sent while the gate's paths to off are in doubt, so nothing more is swept).</summary>
    Task StopStageAsync();
}
