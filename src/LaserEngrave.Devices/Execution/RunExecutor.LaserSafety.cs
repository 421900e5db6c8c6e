using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Motion;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Zaber;
using LaserEngrave.Wire.Scheduling;

namespace LaserEngrave.Devices.Execution;

/// <summary>Laser safety: every laser command under one lock, the keepalive's failure, the off sequence on abort and fault, the stage stopped.</summary>
public sealed partial class RunExecutor
{
    private async Task AbortSequenceAsync()
    {
        try
        {
            await LaserOffSafelyAsync();
            await StopAxesAsync();
        }
        finally
        {
            // Releases whatever the run is waiting for (a move the stop did not interrupt, a pause).
            _abortDone.Cancel();
        }
    }

    private void OnKeepAliveFailed(Exception ex) => _fault.Cancel();

    private async Task SwitchLaserAsync(bool on)
    {
        await _laserLock.WaitAsync();
        try
        {
            if (on)
            {
                // Inside the lock: an abort's switch-off is either already sent (and we stop here) or comes after this.
                ThrowIfAborted();

                // Gate commands are not cancelled: a reply arriving after a cancelled command would be taken for the next one's.
                await Gate.SetFrequencyAsync(_process.LaserFrequencyWholeHz, CancellationToken.None);
                lock (_lock)
                {
                    _laserOn = true;
                    _laserOnSince = TimeProvider.GetTimestamp();
                }

                // Timed runs feed the watchdog in their own gate schedule, between the timed commands.
                _keepAlive!.Active = _timing is null;
            }
            else
            {
                if (_keepAlive is not null)
                {
                    _keepAlive.Active = false;
                }

                try
                {
                    await Gate.OffAsync(CancellationToken.None);
                }
                catch (DeviceException)
                {
                    MarkSwitchOffFailed();
                    throw;
                }

                MarkLaserOff();
            }
        }
        finally
        {
            _laserLock.Release();
        }
    }

    /// <summary>A switch-off was refused or not acknowledged: the fault's off sequence takes every path at once.</summary>
    private void MarkSwitchOffFailed()
    {
        lock (_lock)
        {
            _switchOffFailed = true;
        }
    }

    private void MarkLaserOff(double leadSeconds = 0)
    {
        lock (_lock)
        {
            if (_laserOn)
            {
                _laserOnSeconds += Math.Max(0, TimeProvider.GetElapsedTime(_laserOnSince).TotalSeconds + leadSeconds);
                _laserOn = false;
            }
        }
    }

    /// <summary>
    /// Switches the laser off after a fault or an abort: OFF, and when that (or an earlier switch-off) was refused or went
    /// unanswered, every other path at once (<see cref="EveryWayOffAsync"/>); records which one the gate confirmed.
    /// </summary>
    private async Task LaserOffSafelyAsync()
    {
        await _laserLock.WaitAsync();
        try
        {
            if (_keepAlive is not null)
            {
                _keepAlive.Active = false;
            }
            bool inDoubt;
            lock (_lock)
            {
                if (_engravingStarted)
                {
                    _faultOffWrite ??= RunSeconds;
                }

                // Every path was taken once already: the laser is confirmed off, or its port is closed and a person must check it.
                if (_laserOffBy is LaserOffPath.OffAgain or LaserOffPath.FrequencyZero or LaserOffPath.None)
                {
                    return;
                }

                inDoubt = _switchOffFailed;

                // A switch-off refused or unanswered after the burn run's burst had stopped the laser by itself: the run's
                // last pulse was the burst's, inside the run; the paths to off below still go, and say which confirmed it.
                _burstEndedItself |= inDoubt && RunSeconds >= _burstEndsAt;
            }

            DeviceException? refused = null;
            Task? first = null;
            if (!inDoubt)
            {
                first = Gate.OffAsync(CancellationToken.None);

                // Answered within its round trip (and the margin a stage reply gets), or it is in doubt: a gate gone deaf
                // must not leave the stage sweeping for the whole of the gate's timeout with the laser on.
                var roundTrip = (_timing?.OffRoundTripSeconds ?? 0.02) + (2 * (_timing?.GateJitterSeconds ?? 0)) + (Options.StallMarginMs / 1000);
                using (var wait = new CancellationTokenSource())
                {
                    await Task.WhenAny(first, PreciseDelay.DelayAsync(TimeProvider, TimeSpan.FromSeconds(roundTrip), wait.Token));
                    wait.Cancel();
                }

                if (first.IsCompletedSuccessfully)
                {
                    MarkLaserOff();
                    lock (_lock)
                    {
                        _laserOffConfirmed = true;
                        _laserOffProblem = null;
                        _laserOffBy = LaserOffPath.Off;
                    }

                    return;
                }

                refused = first.Exception?.InnerException as DeviceException;
            }

            await EveryWayOffAsync(refused, first);
        }
        finally
        {
            _laserLock.Release();
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
        var off = Gate.OffAsync(CancellationToken.None);
        var zero = Gate.SetFrequencyAsync(0, CancellationToken.None);
        var watchdog = Gate.SetWatchdogAsync(MachineProfileValidator.MinWatchdogMs, CancellationToken.None);
        var stopping = StopAxesAsync();
        await Task.WhenAll(Settled(first ?? Task.CompletedTask), Settled(off), Settled(zero), Settled(watchdog), stopping);
        var path = off.IsCompletedSuccessfully || first?.IsCompletedSuccessfully == true ? LaserOffPath.OffAgain
            : zero.IsCompletedSuccessfully ? LaserOffPath.FrequencyZero
            : LaserOffPath.None;
        MarkLaserOff();
        if (path == LaserOffPath.None && Gate is IAsyncDisposable port)
        {
            // Silence on its line is the one thing left that switches the laser off: the gate's own watchdog.
            await port.DisposeAsync();
        }

        lock (_lock)
        {
            _laserOffBy = path;
            _laserOffConfirmed = path != LaserOffPath.None;
            var why = (refused ?? off.Exception?.InnerException ?? zero.Exception?.InnerException)?.Message;
            _laserOffProblem = path != LaserOffPath.None ? null : string.Create(
                CultureInfo.InvariantCulture,
                $"the laser could not be confirmed off: the gate acknowledged neither OFF nor FREQ 0 ({why}); its port was closed so that its watchdog ({(watchdog.IsCompletedSuccessfully ? MachineProfileValidator.MinWatchdogMs : _profile.Gate.WatchdogMs)} ms) switches the laser off; a person must check the laser");
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

    private async Task StopAxesAsync()
    {
        var known = true;
        foreach (var axis in new[] { Stage.X, Stage.Y })
        {
            try
            {
                var written = _engravingStarted ? RunSeconds : double.NaN;
                var position = await axis.StopAsync(CancellationToken.None);
                if (axis == Stage.X)
                {
                    NoteStopped(written, position);
                }

                lock (_lock)
                {
                    if (axis == Stage.X)
                    {
                        _x = position;
                    }
                    else
                    {
                        _y = position;
                    }
                }
            }
            catch (DeviceException)
            {
                // The stage may be gone (port lost, silent): the stop point then has no position.
                known = false;
            }
        }

        lock (_lock)
        {
            _stoppedAtKnownPosition = known;
        }
    }
}
