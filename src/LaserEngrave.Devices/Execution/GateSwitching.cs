using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.Devices.Execution;

/// <summary>What <see cref="GateSwitching"/> asks of the run it switches the laser for.</summary>
internal interface IGateSwitchingRun
{
    /// <summary>Seconds since the engraving started, on the run's clock.</summary>
    double RunSeconds { get; }

    /// <summary>When the engraving started, a timestamp of the run's clock.</summary>
    long EngravingStart { get; }

    /// <summary>Throws when the run was aborted or a fault ended it: nothing more is switched on.</summary>
    void ThrowIfEnded();

    /// <summary>Ends the run at a fault, laser off first; returns the exception to throw.</summary>
    DeviceException Fault(string reason, bool recoverable);

    /// <summary>Waits until <paramref name="seconds"/> run seconds.</summary>
    Task DelayUntilAsync(double seconds, CancellationToken token);
}

/// <summary>
/// The timed laser's lines on the gate's wire (docs/execution.md, "The burst"): each switch-on a counted burst sized
/// when it is written, or scheduled ahead for the gate to time itself, each switch-off under the laser lock, and what is
/// still on the gate's wire and its replies' way back, so that a switch-off is expected after the lines ahead of it.
/// Late writes are counted (<see cref="Late"/>) and, beyond the edge tolerance, end the run as a timing doubt.
/// </summary>
/// <remarks>
/// One per run, on the run's thread; what the abort's and the fault's paths read (<see cref="BurstEndsAt"/>,
/// <see cref="BurstEndedItself"/>, <see cref="Late"/>) is written under the engine's lock.
/// </remarks>
internal sealed class GateSwitching(ILaserGate gate, LaserSafety laser, TimeProvider time, MachineProfile profile, Lock engineLock, IGateSwitchingRun run)
{
    /// <summary>How late a timed command may be written before it counts as late (below that: the clock's rounding), s.</summary>
    public const double LateSeconds = 0.0001;

    private readonly ILaserGate _gate = gate;
    private readonly LaserSafety _laser = laser;
    private readonly TimeProvider _time = time;
    private readonly MachineProfile _profile = profile;
    private readonly Lock _lock = engineLock;
    private readonly IGateSwitchingRun _run = run;

    /// <summary>When the gate's wire is free of the lines written so far (the host's estimate at the adapter's mean), run seconds.</summary>
    public double WireFree { get; private set; } = double.NegativeInfinity;

    /// <summary>When the gate's replies to the lines written so far are all in (the same estimate): an off written now is answered after them.</summary>
    public double RepliesIn { get; private set; } = double.NegativeInfinity;

    /// <summary>When the last burst stops by itself at the latest, run seconds (under the engine's lock).</summary>
    public double BurstEndsAt { get; private set; } = double.NegativeInfinity;

    /// <summary>Whether the laser's last burst had stopped it by itself when a switch-off was in doubt (under the engine's lock).</summary>
    public bool BurstEndedItself { get; set; }

    /// <summary>The switchings written late but within the edge tolerance (under the engine's lock); null when none.</summary>
    public LateSwitches? Late { get; private set; }

    /// <summary>When the host last wrote to the gate, run seconds (keepalives go a period after it).</summary>
    public double LastWrite { get; set; }

    /// <summary>Whether this run's switch-ons are scheduled bursts the gate times (its CAPS? lists AFTER).</summary>
    public bool ScheduledBursts { get; set; }

    /// <summary>How much later than its round trip an OFF written at <paramref name="now"/> is answered, behind the lines and replies still on the gate's wire.</summary>
    public double QueueSeconds(TimedSwitching timing, double now) => timing.OffQueuedSeconds(now, WireFree, RepliesIn);

    /// <summary>A keepalive written at <paramref name="written"/>: its line and its reply join the gate's wire.</summary>
    public void KeepAliveWritten(double written, TimedSwitching timing)
    {
        WireFree = timing.GateWireFreeAfter(written, WireFree, timing.KeepAliveBytes);
        RepliesIn = timing.GateRepliesInAfter(WireFree, RepliesIn, timing.KeepAliveReplyBytes);
    }

    /// <summary>When a stage command planned to arrive at <paramref name="plannedArrival"/> arrives, written at <paramref name="writtenSeconds"/>.</summary>
    /// <remarks>A host late to write (a loaded computer) is not the device's delay: its reply is expected that much later.</remarks>
    public static double Sent(double plannedArrival, double writtenSeconds, TimedSwitching timing) =>
        Later(plannedArrival, writtenSeconds + timing.StageCommandSeconds);

    /// <summary>The actual time when it is later than planned by more than the clock's rounding, else the planned one.</summary>
    public static double Later(double planned, double actual) => actual > planned + LateSeconds ? actual : planned;

    /// <summary>
    /// Sends a timed switch-on under the laser lock (after checking for an abort) and returns its acknowledgement without
    /// waiting for it, and when it was written: the lock is free again at once, so an abort's or a fault's switch-off never
    /// waits behind it. The switch-on is the gate's counted burst, sized now, from the real write time and the gate's wire
    /// queue, to stop by itself before <paramref name="offEffect"/> (docs/execution.md, "The burst"): a switch-off that is
    /// late, refused or lost then costs no pulse past the edge. A host so late that it is beyond the profile's edge
    /// tolerance (or that no pulse fits any more) leaves the laser off and ends the run as a timing doubt.
    /// </summary>
    public async Task<(Task Acknowledged, double WrittenSeconds)> SendSwitchOnAsync(double onEffect, double offEffect, TimedSwitching timing)
    {
        var sent = await SendSwitchOnLockedAsync(onEffect, offEffect, timing);
        await LateWrite.CheckAsync(sent.LineWritten, _time, _run.EngravingStart, sent.WrittenSeconds, sent.LateSeconds, timing, _profile.EdgeToleranceUm, "switch the laser on", m => _run.Fault(m, recoverable: true));
        return (sent.Acknowledged, sent.WrittenSeconds);
    }

    private async Task<(Task Acknowledged, double WrittenSeconds, double LateSeconds, Task<long?> LineWritten)> SendSwitchOnLockedAsync(double onEffect, double offEffect, TimedSwitching timing)
    {
        await _laser.Lock.WaitAsync();
        try
        {
            _run.ThrowIfEnded();

            // Late is when the gate will start firing against when it was to: the host's own lateness and any line still
            // on the gate's wire ahead of this one.
            var written = _run.RunSeconds;
            var pulses = timing.BurstPulses(written, WireFree, offEffect);
            var late = timing.GateWireFreeAfter(written, WireFree, timing.BurstCommand(Math.Max(1, pulses)).Length) + timing.GateProcessingSeconds - onEffect;
            var lateUm = late * timing.BurnSpeed * timing.MicrostepUm;
            if (lateUm > _profile.EdgeToleranceUm || pulses < 1)
            {
                throw _run.Fault(
                    string.Create(CultureInfo.InvariantCulture, $"this computer was {Units.SecondsToMs(late):0.0} ms late to switch the laser on, {lateUm:0.0} µm at the burn speed, beyond the profile's edge tolerance of {_profile.EdgeToleranceUm:0.###} µm: the laser stayed off for that run"),
                    recoverable: true);
            }

            if (late > LateSeconds)
            {
                NoteLateSwitch(lateUm);
            }

            // A frequency-only gate is switched on by its frequency alone, as before the burst: only the timed switch-off ends the run.
            var counted = _profile.Gate.CountsBursts;
            var ack = counted ? _gate.BurstAsync(pulses, timing.FrequencyHz, CancellationToken.None) : _gate.SetFrequencyAsync(timing.FrequencyHz, CancellationToken.None);
            var lineWritten = _gate.LineWritten;
            WireFree = timing.GateWireFreeAfter(written, WireFree, timing.BurstCommand(pulses).Length);
            RepliesIn = timing.GateRepliesInAfter(WireFree, RepliesIn, timing.BurstReplyBytes(pulses));
            var firing = WireFree + timing.GateProcessingSeconds;
            lock (_lock)
            {
                _laser.MarkOn(_time.GetTimestamp() + (long)((firing - written) * _time.TimestampFrequency));
                BurstEndsAt = counted ? firing + ((double)pulses / timing.FrequencyHz) + timing.GateJitterSeconds : double.PositiveInfinity;
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
    public async Task<(Task Acknowledged, double WrittenSeconds, double AnsweredSeconds)> PlainSwitchOnAsync(double onEffect, double offEffect, double onWrite, TimedSwitching timing, CancellationToken token)
    {
        await _run.DelayUntilAsync(onWrite, token);
        var (on, written) = await SendSwitchOnAsync(onEffect, offEffect, timing);
        return (on, written, Later(onWrite, written) + timing.OnRoundTripSeconds);
    }

    /// <summary>
    /// A switch-on the gate times itself (<c>BURST n hz AFTER us</c>, docs/laser-gate-protocol.md "Scheduled bursts"):
    /// written its slack ahead of time, with the delay computed at the write from when it is written, the lines still on
    /// the gate's wire and the gate's processing, so that a host late by less than the slack moves no edge. Written too
    /// late for that, it is the plain switch-on at its own time, with the edge tolerance as before.
    /// </summary>
    public async Task<(Task Acknowledged, double WrittenSeconds, double AnsweredSeconds)> ScheduledSwitchOnAsync(double onEffect, double offEffect, double onWrite, TimedSwitching timing, CancellationToken token)
    {
        await _run.DelayUntilAsync(Math.Min(timing.ScheduledWriteSeconds(onEffect, offEffect, BurstEndsAt), onWrite), token);
        for (var attempt = 0; attempt < 3; attempt++)
        {
            if (await SendScheduledSwitchOnAsync(onEffect, offEffect, timing) is { } sent)
            {
                // Its delay was computed at the stamp: a write that completed later (a computer stalled between them)
                // reached the gate that much later and fires that much late, its count ending past the edge. Beyond the
                // tolerance that is a timing doubt: the fault's OFF cancels the armed burst before or as it fires.
                await LateWrite.CheckAsync(sent.LineWritten, _time, _run.EngravingStart, sent.WrittenSeconds, 0, timing, _profile.EdgeToleranceUm, "switch the laser on", m => _run.Fault(m, recoverable: true));
                return (sent.Acknowledged, sent.WrittenSeconds, sent.AnsweredSeconds);
            }

            // A delay just at a power of ten (its digits and the line's length disagree) is tried again a moment later.
            var again = _run.RunSeconds + (2 * timing.GateByteSeconds);
            if (again >= onWrite)
            {
                break;
            }

            await _run.DelayUntilAsync(again, token);
        }

        return await PlainSwitchOnAsync(onEffect, offEffect, onWrite, timing, token);
    }

    /// <summary>Writes a scheduled switch-on under the laser lock if it is still in time for the gate's timer; null when not (nothing written).</summary>
    private async Task<(Task Acknowledged, double WrittenSeconds, double AnsweredSeconds, Task<long?> LineWritten)?> SendScheduledSwitchOnAsync(double onEffect, double offEffect, TimedSwitching timing)
    {
        await _laser.Lock.WaitAsync();
        try
        {
            _run.ThrowIfEnded();

            // Computed at the write itself: whatever the host lost before it comes off the delay, not off the edge.
            var written = _run.RunSeconds;
            if (timing.Schedule(written, WireFree, onEffect, offEffect) is not { } burst)
            {
                return null;
            }

            var ack = _gate.BurstAfterAsync(burst.Pulses, timing.FrequencyHz, burst.AfterUs, CancellationToken.None);
            var lineWritten = _gate.LineWritten;
            WireFree = burst.ArrivalSeconds;
            RepliesIn = timing.GateRepliesInAfter(WireFree, RepliesIn, timing.BurstAfterReplyBytes(burst.Pulses, burst.AfterUs));
            var firing = burst.ArrivalSeconds + (burst.AfterUs / 1e6);
            lock (_lock)
            {
                _laser.MarkOn(_time.GetTimestamp() + (long)((firing - written) * _time.TimestampFrequency));
                BurstEndsAt = firing + ((double)burst.Pulses / timing.FrequencyHz) + timing.GateJitterSeconds;
            }

            return (ack, written, RepliesIn + timing.GateJitterSeconds, lineWritten);
        }
        finally
        {
            _laser.Lock.Release();
        }
    }

    /// <summary>Sends a timed switch-off under the laser lock and returns its acknowledgement without waiting for it, and when it was written.</summary>
    public async Task<(Task Acknowledged, double WrittenSeconds)> SendSwitchOffAsync(TimedSwitching timing)
    {
        await _laser.Lock.WaitAsync();
        try
        {
            var written = _run.RunSeconds;

            // Counted from effect to effect: the switch-off takes effect its lead after it is sent, as the switch-on did.
            var off = _gate.OffAsync(CancellationToken.None);
            WireFree = timing.GateWireFreeAfter(written, WireFree, timing.OffCommand.Length);
            RepliesIn = timing.GateRepliesInAfter(WireFree, RepliesIn, timing.OffReplyBytes);
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
            Late = LateSwitches.Add(Late, off ? new LateSwitches(0, 0, _profile.EdgeToleranceUm, 1) : new LateSwitches(1, lateUm, _profile.EdgeToleranceUm));
        }
    }

    /// <summary>
    /// A switch-off written late: the burst has stopped the laser by itself at the run's end already, so no pulse crossed
    /// the edge; it is counted and logged, beside the late switch-ons. A frequency-only gate has no burst: beyond the edge
    /// tolerance its laser fired past the edge, and the run ends.
    /// </summary>
    public void NoteSwitchOffLate(double planned, double written, TimedSwitching timing)
    {
        var late = written - planned;
        if (late > LateSeconds)
        {
            var lateUm = late * timing.BurnSpeed * timing.MicrostepUm;
            NoteLateSwitch(lateUm, off: true);
            if (!_profile.Gate.CountsBursts && lateUm > _profile.EdgeToleranceUm)
            {
                // A frequency-only gate fires until the switch-off arrives: late beyond the tolerance, it fired past the edge.
                throw _run.Fault(
                    string.Create(
                        CultureInfo.InvariantCulture,
                        $"this computer was {Units.SecondsToMs(late):0.0} ms late to switch the laser off, {lateUm:0.0} µm at the burn speed, beyond the profile's edge tolerance of {_profile.EdgeToleranceUm:0.###} µm: this frequency-only gate fired past the run's exit edge"),
                    recoverable: false);
            }
        }
    }
}
