using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Wire.Scheduling;

namespace LaserEngrave.Devices.Execution;

/// <summary>
/// The one laser-off path: a run's fault and abort (<see cref="LaserSafety"/>), the end of every test move
/// (<see cref="StageTestMoves"/>) and the app closing all switch the laser off through it. OFF, confirmed within its
/// round trip; when it is not (refused, unanswered in time, or an earlier switch-off was), OFF again, FREQ 0 and the
/// shortest watchdog go out together as emergency commands (<see cref="ILaserGate.EmergencyAsync"/>: nothing on the link
/// holds them up), the stage stopped meanwhile; when the gate acknowledges neither OFF nor FREQ 0, its port is closed so
/// that its own watchdog switches the laser off.
/// </summary>
/// <remarks>
/// Nothing here throws: every failure of the gate (a refusal, a timeout, a lost link, a closed or disposed port, a bug)
/// is settled into the <see cref="LaserOffResult"/>. docs/execution.md ("Safety") describes the sequence.
/// </remarks>
public sealed class LaserOff
{
    private readonly ILaserGate _gate;
    private readonly TimeProvider _time;

    public LaserOff(ILaserGate gate, TimeProvider? timeProvider = null)
    {
        ArgumentNullException.ThrowIfNull(gate);
        _gate = gate;
        _time = timeProvider ?? TimeProvider.System;
    }

    /// <summary>
    /// The gate never replies (a frequency-only gate whose profile says so): its commands count as carried out once
    /// written, so the laser is never reported confirmed off, only sent off.
    /// </summary>
    public bool GateNeverReplies { get; set; }

    /// <summary>
    /// How long a switch-off may take to be acknowledged before it is in doubt: its round trip on the gate's line, twice
    /// the gate's jitter and the stall margin (the test a timed run's own switch-offs get, docs/execution.md), and the
    /// time the lines and replies still ahead of it on the gate's wire take (<paramref name="queuedSeconds"/>).
    /// </summary>
    public static TimeSpan ConfirmWindow(TimedSwitching timing, double stallMarginMs, double queuedSeconds = 0)
    {
        ArgumentNullException.ThrowIfNull(timing);
        return TimeSpan.FromSeconds(timing.OffRoundTripSeconds + (2 * timing.GateJitterSeconds) + Units.MsToSeconds(stallMarginMs) + Math.Max(0, queuedSeconds));
    }

    /// <summary>The window for a machine's gate at its process' settings and the default stall margin.</summary>
    public static TimeSpan ConfirmWindow(ProcessSettings process, MachineProfile profile) =>
        ConfirmWindow(TimedSwitching.For(process, profile, profile.X.MicrostepUm), RunOptions.Default.StallMarginMs);

    /// <summary>Switches the laser off: OFF, and every path at once when that is not acknowledged within <paramref name="window"/>.</summary>
    /// <param name="window">How long the OFF may take (<see cref="ConfirmWindow(TimedSwitching, double, double)"/>).</param>
    /// <param name="watchdogMs">The gate's watchdog time, named when only the watchdog is left to switch the laser off.</param>
    /// <param name="stopStage">Stops the stage, sent with the emergency commands so that nothing more is swept; null: none.</param>
    public async Task<LaserOffResult> SwitchOffAsync(TimeSpan window, int watchdogMs, Func<Task>? stopStage = null)
    {
        var first = Start(() => _gate.EmergencyAsync(EmergencyCommand.Off, CancellationToken.None));
        using (var wait = new CancellationTokenSource())
        {
            await Task.WhenAny(first, PreciseDelay.DelayAsync(_time, window, wait.Token));
            wait.Cancel();
        }

        if (first.IsCompletedSuccessfully)
        {
            return new LaserOffResult(LaserOffPath.Off, GateNeverReplies ? NeverRepliesProblem("OFF was") : null);
        }

        return await EveryWayOffAsync(first.IsFaulted ? first.Exception?.InnerException : null, first, watchdogMs, stopStage);
    }

    /// <summary>
    /// A switch-off was refused or went unanswered (<paramref name="refused"/> why, when known): OFF again, FREQ 0 and the
    /// shortest watchdog go out together with the stage's stop; the first of OFF (<paramref name="pending"/>, the one still
    /// waiting, included) and FREQ 0 the gate acknowledges confirms the laser off. When neither is, the gate's port is closed.
    /// </summary>
    public async Task<LaserOffResult> EveryWayOffAsync(Exception? refused, Task? pending, int watchdogMs, Func<Task>? stopStage = null)
    {
        // Gate commands are not cancelled (a late reply would be taken for the next one's): each waits its own timeout.
        var off = Start(() => _gate.EmergencyAsync(EmergencyCommand.Off, CancellationToken.None));
        var zero = Start(() => _gate.EmergencyAsync(EmergencyCommand.FrequencyZero, CancellationToken.None));
        // A gate without a watchdog (frequency-only) has none to shorten.
        var watchdog = watchdogMs > 0 ? Start(() => _gate.EmergencyAsync(EmergencyCommand.ShortestWatchdog, CancellationToken.None)) : Task.CompletedTask;
        var stopping = stopStage is null ? Task.CompletedTask : Start(stopStage);
        await Task.WhenAll(Settled(pending ?? Task.CompletedTask), Settled(off), Settled(zero), Settled(watchdog), Settled(stopping));
        var path = off.IsCompletedSuccessfully || pending?.IsCompletedSuccessfully == true ? LaserOffPath.OffAgain
            : zero.IsCompletedSuccessfully ? LaserOffPath.FrequencyZero
            : LaserOffPath.None;
        if (path != LaserOffPath.None)
        {
            return new LaserOffResult(path, GateNeverReplies ? NeverRepliesProblem("OFF and FREQ 0 were") : null)
            {
                AllAnswered = off.IsCompletedSuccessfully && zero.IsCompletedSuccessfully && watchdog.IsCompletedSuccessfully && pending?.IsCompletedSuccessfully != false,
            };
        }

        // Silence on its line is the one thing left that switches the laser off: the gate's own watchdog.
        await Settled(Start(async () => await _gate.CloseAsync()));
        var why = (refused ?? off.Exception?.InnerException ?? zero.Exception?.InnerException)?.Message;
        if (watchdogMs <= 0)
        {
            return new LaserOffResult(LaserOffPath.None, $"the laser could not be confirmed off: the gate acknowledged neither OFF nor FREQ 0 ({why}), and it has no watchdog; a person must switch the laser off at its key now");
        }

        return new LaserOffResult(LaserOffPath.None, string.Create(
            CultureInfo.InvariantCulture,
            $"the laser could not be confirmed off: the gate acknowledged neither OFF nor FREQ 0 ({why}); its port was closed so that its watchdog ({(watchdog.IsCompletedSuccessfully ? MachineProfileValidator.MinWatchdogMs : watchdogMs)} ms) switches the laser off; a person must check the laser"));
    }

    private static string NeverRepliesProblem(string sent) =>
        $"the laser could not be confirmed off: {sent} sent, but this laser gate never replies; a person must check the laser";

    // A call that throws before it returns its task (a disposed port, a bug) fails that task instead: nothing escapes the off path.
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

    private static async Task Settled(Task task)
    {
        try
        {
            await task;
        }
        catch (Exception)
        {
            // Every failure is looked at through the task itself.
        }
    }
}

/// <summary>How the laser was switched off: the path the gate confirmed, or none and why.</summary>
/// <param name="Path">Which command the gate acknowledged; <see cref="LaserOffPath.None"/>: none, its port was closed.</param>
/// <param name="Problem">Why the laser could not be confirmed off, one line; null when it was.</param>
public sealed record LaserOffResult(LaserOffPath Path, string? Problem)
{
    /// <summary>The gate acknowledged a path to off (a gate that never replies never confirms: its problem says so).</summary>
    public bool Confirmed => Path != LaserOffPath.None && Problem is null;

    /// <summary>Every command of the sequence was acknowledged, the switch-off in doubt too: the gate was only late.</summary>
    public bool AllAnswered { get; init; }
}
