using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Motion;
using LaserEngrave.Core.Programs;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Core.Planning;

/// <summary>
/// The timing model of an optimized run: when each command must leave the host so that the stage and the laser act at
/// the right moment, how long a run-up must be, and whether a gap is crossed at the burn speed or by a stop-go travel.
/// </summary>
/// <remarks>
/// <para>
/// The executor (Devices/Execution/RunExecutor) sends its commands at the times computed here and
/// <see cref="PlanEstimator"/> adds up the same times, so the estimate models what the executor does by construction.
/// docs/execution.md explains the model; all times are seconds, all distances microsteps.
/// </para>
/// <para>
/// A command takes effect when its last byte has arrived: the adapter's latency (the profile's <c>latency</c> section)
/// plus its bytes at the baud rate (10 bits a byte), plus the gate's processing time for a gate command. A motion is
/// a Zaber trapezoid from rest to rest at the quantised speed and acceleration.
/// </para>
/// </remarks>
public sealed class TimedSwitching
{
    /// <summary>Most pulses one <c>BURST</c> may count (docs/laser-gate-protocol.md); a longer burn run is refused before anything moves.</summary>
    public const int MaxBurstPulses = 1_000_000;


    // Time the host allows itself to react to a reply before acting on it.
    private const double ReactionSeconds = 0.0005;

    private readonly double _gateByteSeconds;
    private readonly double _gateAdapterSeconds;
    private readonly double _gateProcessingSeconds;
    private readonly MachineProfile _profile;

    // A plan asks these of every gap; they depend on the gap's length alone.
    private readonly GapMemo<FlownGap?> _flown;
    private readonly GapMemo<bool> _crossesGap;

    /// <summary>The process this model times.</summary>
    public ProcessSettings Process { get; }

    /// <summary>The machine whose latencies and gate commands it times.</summary>
    public MachineProfile Profile { get; }

    /// <param name="process">The process timed.</param>
    /// <param name="profile">The machine's latencies and gate commands.</param>
    /// <param name="microstepUm">The stage's microstep, µm.</param>
    /// <param name="scheduledSwitchOns">
    /// Whether a flown gap leaves room after its position query for a scheduled switch-on's longer line and its slack;
    /// null: on every gate that counts its bursts, since whether it takes scheduled bursts is only known when the run asks
    /// it (CAPS?), and the plan, its estimate and the run must agree. A gate without them switches on plainly in that room.
    /// </param>
    public TimedSwitching(ProcessSettings process, MachineProfile profile, double microstepUm, bool? scheduledSwitchOns = null)
    {
        ArgumentNullException.ThrowIfNull(process);
        ArgumentNullException.ThrowIfNull(profile);
        var latency = profile.Latency;
        var gate = profile.Gate;
        MicrostepUm = microstepUm;
        Process = process;
        Profile = profile;
        (BurnSpeedData, TravelSpeedData, AccelerationData) = MotionData.Of(process, PlanStrategy.Optimized, microstepUm);
        BurnSpeed = StageUnits.SpeedMicrostepsPerS(BurnSpeedData);
        TravelSpeed = StageUnits.SpeedMicrostepsPerS(TravelSpeedData);
        Acceleration = StageUnits.AccelerationMicrostepsPerS2(AccelerationData);

        var stageByte = SerialLine.BitsPerByte / process.StageBaudRate;
        FrameSeconds = ZaberFrame.Length * stageByte;
        StageAdapterSeconds = Units.MsToSeconds(latency.StageMs);
        StageJitterSeconds = Units.MsToSeconds(latency.StageJitterMs);
        StageCommandSeconds = StageAdapterSeconds + FrameSeconds;
        StageReplySeconds = FrameSeconds + StageAdapterSeconds;

        var gateByte = SerialLine.BitsPerByte / process.GateBaudRate;
        var frequency = process.LaserFrequencyWholeHz;
        FrequencyHz = frequency;
        _profile = profile;
        _gateByteSeconds = gateByte;

        // Every timed switch-on is a counted burst (docs/execution.md, "The burst"): the planning bounds (run-up, flown
        // gaps, shortest gap) take the longest burst a run across the whole X travel can need; each switch-on is then
        // timed by its own line's length.
        var longestRun = profile.X.TravelMicrosteps / Math.Max(1, BurnSpeed) * Math.Max(1, frequency);
        LongestBurstPulses = (int)Math.Clamp(Math.Ceiling(longestRun), 1, MaxBurstPulses);
        OnCommand = BurstCommand(LongestBurstPulses);
        OffCommand = gate.OffCommand + gate.LineTerminator;
        var onReply = BurstReply(LongestBurstPulses);
        var offReply = gate.AckPrefix + " " + gate.OffReply + gate.LineTerminator;
        var ping = gate.KeepAliveCommand + gate.LineTerminator;
        var pong = gate.AckPrefix + " " + gate.KeepAliveReply + gate.LineTerminator;
        var gateAdapter = Units.MsToSeconds(latency.GateMs);
        var processing = Units.MsToSeconds(latency.GateProcessingMs);
        _gateAdapterSeconds = gateAdapter;
        _gateProcessingSeconds = processing;
        GateJitterSeconds = Units.MsToSeconds(latency.GateJitterMs + latency.GateProcessingJitterMs);
        HalfPulseSeconds = 0.5 / Math.Max(1, frequency);
        OnLeadSeconds = gateAdapter + (OnCommand.Length * gateByte) + processing;
        OffLeadSeconds = gateAdapter + (OffCommand.Length * gateByte) + processing;
        OnRoundTripSeconds = OnLeadSeconds + (onReply.Length * gateByte) + gateAdapter;
        KeepAliveBytes = ping.Length;
        KeepAliveReplyBytes = pong.Length;
        OffReplyBytes = offReply.Length;
        OffRoundTripSeconds = OffLeadSeconds + (offReply.Length * gateByte) + gateAdapter;
        KeepAliveRoundTripSeconds = gateAdapter + (ping.Length * gateByte) + processing + (pong.Length * gateByte) + gateAdapter;

        // A move is sent so that it arrives after the motion before it has ended, whatever both latencies drew.
        MarginSeconds = (2 * StageJitterSeconds) + ReactionSeconds;

        // From a stroke's start (its Move Absolute arriving): the position query sent right behind it comes back; then the
        // switch-on needs its lead. The laser is never switched on before the stage has been seen moving.
        PollReplySeconds = FrameSeconds + StageReplySeconds + (2 * StageJitterSeconds) + ReactionSeconds;
        var ramp = BurnSpeed / Acceleration;
        // A scheduled switch-on needs its longer line and its slack after the query's reply (the stroke's first run and
        // every run after a flown gap): room a plain one leaves unused.
        ScheduledSwitchOns = (scheduledSwitchOns ?? true) && gate.CountsBursts;
        ScheduledExtraSeconds = ScheduledSwitchOns
            ? (Math.Max(0, BurstAfterCommand(LongestBurstPulses, (int)(ScheduleSlackSeconds * 1e6)).Length - OnCommand.Length) * gateByte) + PlannedSlackSeconds + ScheduleMinSeconds
            : 0;
        FirstEdgeSeconds = Math.Max(ramp + ReactionSeconds, PollReplySeconds + OnLeadSeconds + ScheduledExtraSeconds + GateJitterSeconds);
        RunUpMicrosteps = (long)Math.Ceiling((BurnSpeed * BurnSpeed / (2 * Acceleration)) + (BurnSpeed * (FirstEdgeSeconds - ramp)));
        RunOutMicrosteps = (long)Math.Ceiling(BurnSpeed * BurnSpeed / (2 * Acceleration));

        // Switchings are sent without waiting for the acknowledgement before them, but one line must have left the wire
        // before the next may: a switch-off can follow a switch-on no sooner than its own bytes take, and the other way round.
        OffWireSeconds = OffCommand.Length * gateByte;
        OnWireSeconds = OnCommand.Length * gateByte;
        LateOffAllowanceSeconds = gate.CountsBursts ? 0 : profile.EdgeToleranceUm / (BurnSpeed * microstepUm);
        MinOnSeconds = (2 * EdgeGuardSeconds) + LateOffAllowanceSeconds + OffWireSeconds + (2 * GateJitterSeconds) + ReactionSeconds;
        MinOffSeconds = MinOffFor(LongestBurstPulses);
        _flown = new GapMemo<FlownGap?>(gap => ComputeFly(gap) is { } fly ? FlownGap.Of(this, fly) : null);
        _crossesGap = new GapMemo<bool>(gap => CrossSeconds(gap) <= StopGoSeconds(gap));
    }

    public double MicrostepUm { get; }

    /// <summary>Whether flown gaps are planned with room for scheduled switch-ons (<see cref="Schedule"/>).</summary>
    public bool ScheduledSwitchOns { get; }

    /// <summary>How much more a scheduled switch-on needs after a flown gap's query than a plain one: its longer line and its slack (0 for plain switch-ons).</summary>
    public double ScheduledExtraSeconds { get; }

    public int BurnSpeedData { get; }

    public int TravelSpeedData { get; }

    public int AccelerationData { get; }

    /// <summary>Burn speed, microsteps/s (quantised).</summary>
    public double BurnSpeed { get; }

    /// <summary>Travel speed, microsteps/s (quantised).</summary>
    public double TravelSpeed { get; }

    /// <summary>Acceleration, microsteps/s² (quantised).</summary>
    public double Acceleration { get; }

    /// <summary>One Zaber frame on the wire.</summary>
    public double FrameSeconds { get; }

    public double StageAdapterSeconds { get; }

    /// <summary>Half-width of the spread of the stage adapter's latency.</summary>
    public double StageJitterSeconds { get; }

    /// <summary>From writing a Zaber command to the device acting on it, when the wire is free.</summary>
    public double StageCommandSeconds { get; }

    /// <summary>From a device sending a reply to the host having it.</summary>
    public double StageReplySeconds { get; }

    /// <summary>The gate's processing, from a line's last byte to the Q-switch changing.</summary>
    public double GateProcessingSeconds => _gateProcessingSeconds;

    /// <summary>Half-width of the spread of a gate command's lead (adapter and processing).</summary>
    public double GateJitterSeconds { get; }

    /// <summary>The longest switch-on line a run can need: the burst over the whole X travel (the planning bounds use it).</summary>
    public string OnCommand { get; }

    /// <summary>The laser's pulse frequency, whole Hz.</summary>
    public int FrequencyHz { get; }

    /// <summary>The pulses of a burst across the whole X travel at the burn speed (at most <see cref="MaxBurstPulses"/>).</summary>
    public int LongestBurstPulses { get; }

    /// <summary>The keepalive line's bytes.</summary>
    public int KeepAliveBytes { get; }

    /// <summary>
    /// The switch-on line of a burst of <paramref name="pulses"/> at the process' frequency; on a frequency-only gate the
    /// frequency command (<c>FREQ f</c>), whatever the count, since the host's timed switch-off ends the run.
    /// </summary>
    public string BurstCommand(int pulses) =>
        _profile.Gate.CountsBursts
            ? string.Format(CultureInfo.InvariantCulture, _profile.Gate.BurstCommand, pulses, FrequencyHz) + _profile.Gate.LineTerminator
            : string.Format(CultureInfo.InvariantCulture, _profile.Gate.FrequencyCommand, FrequencyHz) + _profile.Gate.LineTerminator;

    /// <summary>From writing a burst's line (its wire free) to the gate firing its first pulse.</summary>
    public double BurstLeadSeconds(int pulses) => _gateAdapterSeconds + (BurstCommand(pulses).Length * _gateByteSeconds) + _gateProcessingSeconds;

    /// <summary>From writing a burst's line (its wire free) to its acknowledgement being in.</summary>
    public double BurstRoundTripSeconds(int pulses) => BurstLeadSeconds(pulses) + (BurstReply(pulses).Length * _gateByteSeconds) + _gateAdapterSeconds;

    /// <summary>
    /// The pulses a burst fires in <paramref name="seconds"/>: its instants k / f strictly before the window's end, so the
    /// count is rounded down to the pulses that fall inside (a pulse due at the end itself is not one) and the burst fires
    /// no pulse the timed switch-off would not have let through.
    /// </summary>
    public int PulsesWithin(double seconds) =>
        seconds <= 0 ? 0 : (int)Math.Min(MaxBurstPulses, Math.Floor((seconds * FrequencyHz) - 1e-6) + 1);

    /// <summary>
    /// The burst of a switch-on written at <paramref name="writtenSeconds"/> behind a gate wire busy until
    /// <paramref name="wireFreeSeconds"/>, sized so that its last pulse comes before the run's planned switch-off takes effect
    /// (<paramref name="offEffectSeconds"/>): the largest count whose own line (its length grows with the count's digits)
    /// still fits; 0 when not one pulse does. All times on one clock.
    /// </summary>
    public int BurstPulses(double writtenSeconds, double wireFreeSeconds, double offEffectSeconds)
    {
        var onWire = Math.Max(writtenSeconds + _gateAdapterSeconds, wireFreeSeconds);
        var best = 0;
        for (int digits = 1, least = 1; least <= MaxBurstPulses; digits++, least *= 10)
        {
            var most = (int)Math.Min(MaxBurstPulses, ((long)least * 10) - 1);
            var firing = onWire + (BurstCommand(least).Length * _gateByteSeconds) + _gateProcessingSeconds;
            var pulses = Math.Min(most, PulsesWithin(offEffectSeconds - firing));
            if (pulses >= least)
            {
                best = Math.Max(best, pulses);
            }
        }

        return best;
    }

    /// <summary>
    /// How much earlier than a plain <c>BURST</c> a scheduled switch-on (<c>BURST n hz AFTER us</c>) is written, beyond its
    /// own longer line: the host may be this late to write it and the gate still fires on time (docs/process.md,
    /// "Switch-ons the gate times"). The realistic twin's host is late up to 0.5 ms and one wait in a hundred up to 5 ms;
    /// 20 ms also covers a loaded PC's rarer stalls. A shorter gap before a run leaves less, never more: the line may not
    /// reach the gate before the burst ahead of it has ended (any later frequency command ends a burst).
    /// </summary>
    public const double ScheduleSlackSeconds = 0.020;

    /// <summary>One byte on the gate's wire.</summary>
    public double GateByteSeconds => _gateByteSeconds;

    /// <summary>
    /// The slack a plan leaves for a scheduled switch-on where it must wait for a position query first (a stroke's first
    /// run, a run after a flown gap), where every millisecond is run time: the realistic twin's tail (5 ms) and a margin.
    /// Elsewhere the switch-on is written <see cref="ScheduleSlackSeconds"/> ahead, which costs nothing.
    /// </summary>
    public const double PlannedSlackSeconds = 0.006;

    /// <summary>Least delay a scheduled burst is sent with: the gate's processing of the line, its spread and a margin, so its own timer, not its processing, places the first pulse.</summary>
    public double ScheduleMinSeconds => _gateProcessingSeconds + Units.MsToSeconds(_profile.Latency.GateProcessingJitterMs) + 0.00005;

    /// <summary>The scheduled switch-on's line: <paramref name="pulses"/> at the process' frequency, the first <paramref name="afterUs"/> µs after the line's last byte.</summary>
    public string BurstAfterCommand(int pulses, int afterUs) =>
        string.Format(CultureInfo.InvariantCulture, _profile.Gate.BurstAfterCommand, pulses, FrequencyHz, afterUs) + _profile.Gate.LineTerminator;

    /// <summary>The bytes of a scheduled burst's acknowledgement.</summary>
    public int BurstAfterReplyBytes(int pulses, int afterUs) =>
        _profile.Gate.NeverReplies ? 0 : (_profile.Gate.AckPrefix + " " + string.Format(CultureInfo.InvariantCulture, _profile.Gate.BurstAfterReply, pulses, FrequencyHz, afterUs) + _profile.Gate.LineTerminator).Length;

    /// <summary>
    /// When a scheduled switch-on whose burst fires from <paramref name="onEffectSeconds"/> is best written: its slack
    /// (<see cref="ScheduleSlackSeconds"/>) ahead of the latest moment its line still arrives in time, but never so early
    /// that the line could reach the gate before the burst ahead of it has ended (<paramref name="previousBurstEndsSeconds"/>,
    /// the latest it may end).
    /// </summary>
    public double ScheduledWriteSeconds(double onEffectSeconds, double offEffectSeconds, double previousBurstEndsSeconds)
    {
        var pulses = Math.Max(1, PulsesWithin(offEffectSeconds - onEffectSeconds));
        var bytes = BurstAfterCommand(pulses, (int)Math.Round(ScheduleSlackSeconds * 1e6)).Length;
        var wire = _gateAdapterSeconds + (bytes * _gateByteSeconds);
        var latest = onEffectSeconds - wire - ScheduleMinSeconds - GateJitterSeconds;

        // The line, delivered and processed at the soonest its latencies allow, is taken after that burst's end (its bound already has the spread).
        var earliest = previousBurstEndsSeconds + GateJitterSeconds + ReactionSeconds - wire - _gateProcessingSeconds;
        return Math.Max(latest - ScheduleSlackSeconds, earliest);
    }

    /// <summary>
    /// The scheduled switch-on of a burn run firing from <paramref name="onEffectSeconds"/> to before
    /// <paramref name="offEffectSeconds"/>, written at <paramref name="writtenSeconds"/> behind a gate wire busy until
    /// <paramref name="wireFreeSeconds"/>: its pulses, its delay from the line's arrival (µs, to the gate's time base) and
    /// the line's length; null when it is written too late for the gate's own timer to place the first pulse (the line
    /// arrives with less than <see cref="ScheduleMinSeconds"/> to go), or, rarely, when the delay's digits and the line's
    /// length disagree (a delay just at a power of ten: the caller tries again a moment later).
    /// </summary>
    public ScheduledBurst? Schedule(double writtenSeconds, double wireFreeSeconds, double onEffectSeconds, double offEffectSeconds)
    {
        var pulses = PulsesWithin(offEffectSeconds - onEffectSeconds);
        if (pulses < 1)
        {
            return null;
        }

        var onWire = Math.Max(writtenSeconds + _gateAdapterSeconds, wireFreeSeconds);
        for (int digits = 1, least = 0, most = 9; digits <= 7; digits++, least = most + 1, most = (most * 10) + 9)
        {
            var bytes = BurstAfterCommand(pulses, least).Length;
            var arrival = onWire + (bytes * _gateByteSeconds);
            var delay = onEffectSeconds - arrival;
            var us = (long)Math.Round(delay * 1e6);
            if (us >= least && us <= most)
            {
                return delay < ScheduleMinSeconds || us > MaxAfterUs ? null : new ScheduledBurst(pulses, (int)us, bytes, arrival);
            }
        }

        return null;
    }

    /// <summary>Longest delay of a scheduled burst the gate protocol allows, µs.</summary>
    public const int MaxAfterUs = 1_000_000;

    /// <summary>
    /// Whether the switch-off taking effect at <paramref name="offEffectSeconds"/> leaves the wire in time for the next
    /// burst of <paramref name="nextPulses"/>, taking effect at <paramref name="nextOnEffectSeconds"/>: the next line's bytes
    /// go on the wire behind the switch-off's, whatever both latencies drew. When not, the switch-off is left out.
    /// </summary>
    public bool OffFitsBefore(double offEffectSeconds, double nextOnEffectSeconds, int nextPulses) =>
        nextOnEffectSeconds - offEffectSeconds >= (BurstCommand(Math.Max(1, nextPulses)).Length * _gateByteSeconds) + (2 * GateJitterSeconds) + ReactionSeconds;

    /// <summary>When the switch-on of a burn run is written so that its burst fires from <paramref name="onEffectSeconds"/> to the switch-off's effect, the wire free.</summary>
    public double BurstWriteSeconds(double onEffectSeconds, double offEffectSeconds) =>
        onEffectSeconds - BurstLeadSeconds(Math.Max(1, PulsesWithin(offEffectSeconds - onEffectSeconds)));

    /// <summary>When the gate's wire is free again after <paramref name="bytes"/> written at <paramref name="writtenSeconds"/> behind a wire busy until <paramref name="wireFreeSeconds"/>.</summary>
    public double GateWireFreeAfter(double writtenSeconds, double wireFreeSeconds, int bytes) =>
        Math.Max(writtenSeconds + _gateAdapterSeconds, wireFreeSeconds) + (bytes * _gateByteSeconds);

    /// <summary>
    /// When the gate's replies are all in again after a line whose bytes are on the wire by <paramref name="lineFreeSeconds"/>,
    /// its reply <paramref name="replyBytes"/> long, behind replies in until <paramref name="repliesInSeconds"/>: the gate
    /// answers its lines in order, one reply on its wire at a time.
    /// </summary>
    public double GateRepliesInAfter(double lineFreeSeconds, double repliesInSeconds, int replyBytes) =>
        Math.Max(lineFreeSeconds + _gateProcessingSeconds + _gateAdapterSeconds, repliesInSeconds) + (replyBytes * _gateByteSeconds);

    /// <summary>
    /// How much later than its own round trip an OFF written at <paramref name="writtenSeconds"/> is answered, behind a wire
    /// busy until <paramref name="wireFreeSeconds"/> and replies in until <paramref name="repliesInSeconds"/> (an abort's
    /// OFF written just after a timed switch-on: its reply comes after the burst's).
    /// </summary>
    public double OffQueuedSeconds(double writtenSeconds, double wireFreeSeconds, double repliesInSeconds)
    {
        var answered = GateRepliesInAfter(GateWireFreeAfter(writtenSeconds, wireFreeSeconds, OffCommand.Length), repliesInSeconds, OffReplyBytes);
        return Math.Max(0, answered - (writtenSeconds + OffRoundTripSeconds));
    }

    /// <summary>From writing <c>FREQ f</c> (a step-by-step switch-on) on a free wire to its acknowledgement being in.</summary>
    public double FrequencyRoundTripSeconds(int frequencyHz)
    {
        var gate = _profile.Gate;
        var command = string.Format(CultureInfo.InvariantCulture, gate.FrequencyCommand, frequencyHz) + gate.LineTerminator;
        var reply = gate.AckPrefix + " " + string.Format(CultureInfo.InvariantCulture, gate.FrequencyReply, frequencyHz) + gate.LineTerminator;
        return _gateAdapterSeconds + (command.Length * _gateByteSeconds) + _gateProcessingSeconds + (reply.Length * _gateByteSeconds) + _gateAdapterSeconds;
    }

    /// <summary>The bytes of a burst's acknowledgement.</summary>
    public int BurstReplyBytes(int pulses) => BurstReply(pulses).Length;

    /// <summary>The bytes of the switch-off's acknowledgement.</summary>
    public int OffReplyBytes { get; }

    /// <summary>The bytes of the keepalive's acknowledgement.</summary>
    public int KeepAliveReplyBytes { get; }

    /// <summary>
    /// Null when a burn run of <paramref name="lengthMicrosteps"/> fits in one burst, otherwise the reason in one line: the
    /// gate counts at most <see cref="MaxBurstPulses"/> pulses in a burst, and a run is never left to a timed switch-off alone.
    /// </summary>
    public string? RunTooLongForBurst(long lengthMicrosteps)
    {
        if (!_profile.Gate.CountsBursts)
        {
            // A frequency-only gate counts nothing: the host's switch-off ends every run, however long.
            return null;
        }

        var pulses = Math.Ceiling(lengthMicrosteps / BurnSpeed * FrequencyHz);
        return pulses <= MaxBurstPulses ? null : string.Create(
            CultureInfo.InvariantCulture,
            $"a burn run of {Units.StepsToMm(lengthMicrosteps, MicrostepUm):0.###} mm at the burn speed is {pulses:0} pulses at {FrequencyHz} Hz, more than the {MaxBurstPulses} the laser gate counts in one burst: burn faster, at a lower frequency, or split the run");
    }

    private string BurstReply(int pulses) =>
        _profile.Gate.NeverReplies ? string.Empty
        : _profile.Gate.AckPrefix + " " + (_profile.Gate.CountsBursts
            ? string.Format(CultureInfo.InvariantCulture, _profile.Gate.BurstReply, pulses, FrequencyHz)
            : string.Format(CultureInfo.InvariantCulture, _profile.Gate.FrequencyReply, FrequencyHz)) + _profile.Gate.LineTerminator;

    public string OffCommand { get; }

    /// <summary>
    /// Half a pulse period: the Q-switch fires its first pulse when switched on, so the switch-on comes this long after
    /// the entry edge and the first pulse lands half a pulse spacing inside the run, as the last one does.
    /// </summary>
    public double HalfPulseSeconds { get; }

    /// <summary>
    /// How far inside a run each switching is aimed: the most the gate's and the stage's latencies can move a pulse
    /// relative to the stage, so that no pulse ever lands on the white beyond an edge.
    /// </summary>
    public double EdgeGuardSeconds => GateJitterSeconds + StageJitterSeconds + GuardMarginSeconds;

    // Strictly inside: at the guard itself a pulse can land exactly on the edge.
    private const double GuardMarginSeconds = 0.00002;

    /// <summary>From crossing a run's entry edge to the switch-on taking effect: the guard, at least half a pulse period.</summary>
    public double OnDelaySeconds => Math.Max(HalfPulseSeconds, EdgeGuardSeconds);

    /// <summary>
    /// From the switch-off taking effect to crossing the run's exit edge: the guard, and on a frequency-only gate the
    /// profile's edge tolerance as time at the burn speed too, since nothing but the switch-off stops such a gate and a
    /// computer late to send it within the tolerance must still stop it before the edge.
    /// </summary>
    public double OffAdvanceSeconds => EdgeGuardSeconds + LateOffAllowanceSeconds;

    /// <summary>How late a switch-off may be written and still stop a frequency-only gate before the edge (0 on a gate that counts its bursts).</summary>
    public double LateOffAllowanceSeconds { get; }

    /// <summary>
    /// When a stroke's first switch-on may be sent at the earliest after a Y move's nominal end: once its reply is in.
    /// </summary>
    public double AfterYSeconds => StageReplySeconds + (2 * StageJitterSeconds) + ReactionSeconds;

    /// <summary>From writing the switch-on line to the Q-switch firing.</summary>
    public double OnLeadSeconds { get; }

    /// <summary>From writing the switch-off line to the Q-switch stopping.</summary>
    public double OffLeadSeconds { get; }

    public double OnRoundTripSeconds { get; }

    public double OffRoundTripSeconds { get; }

    public double KeepAliveRoundTripSeconds { get; }

    /// <summary>Between a motion's end and the arrival of the next move on the same axis.</summary>
    public double MarginSeconds { get; }

    /// <summary>From a stroke's start to the latest time the position query's reply is in.</summary>
    public double PollReplySeconds { get; }

    /// <summary>From a stroke's start (at rest) to its first edge.</summary>
    public double FirstEdgeSeconds { get; }

    /// <summary>Run-up before a stroke's first edge: the speed ramp plus the distance covered until the laser may come on.</summary>
    public long RunUpMicrosteps { get; }

    /// <summary>Run-out after a stroke's last edge: the braking distance.</summary>
    public long RunOutMicrosteps { get; }

    /// <summary>The switch-off line on the wire.</summary>
    public double OffWireSeconds { get; }

    /// <summary>The switch-on line on the wire.</summary>
    public double OnWireSeconds { get; }

    /// <summary>Shortest burn run the gate can switch exactly, as time at the burn speed (the guards at both edges and the switch-off's bytes).</summary>
    public double MinOnSeconds { get; }

    /// <summary>Shortest gap between two runs of one stroke that carries both the switch-off and the longest burst line of <see cref="OnCommand"/>, as time at the burn speed.</summary>
    public double MinOffSeconds { get; }

    /// <summary>
    /// Shortest gap before a switch-on whose burst counts <paramref name="pulses"/> that also carries the switch-off's line
    /// ahead of it; in a shorter gap the executor leaves the switch-off out, the burst having ended the run by itself.
    /// </summary>
    public double MinOffFor(int pulses) =>
        (BurstCommand(Math.Max(1, pulses)).Length * _gateByteSeconds) + (2 * GateJitterSeconds) + ReactionSeconds - (2 * EdgeGuardSeconds);

    /// <summary>
    /// Null when one pixel at the burn speed lasts long enough for the gate to switch it exactly, otherwise the reason in
    /// one line (which says how slow the burn must be). The time is the shortest pixel on the wire (whole microsteps), but
    /// the line names the pitch the user set, so it never shows a second, rounded pitch beside theirs.
    /// </summary>
    /// <param name="pixelMicrosteps">The shortest pixel, whole microsteps.</param>
    /// <param name="pitchUm">The pitch the user set.</param>
    /// <param name="longestRunMicrosteps">The job's longest burn run, whose burst line is the longest a gap must carry; absent: one across the whole X travel.</param>
    public string? PixelTooShort(long pixelMicrosteps, double pitchUm, long longestRunMicrosteps = -1)
    {
        var seconds = pixelMicrosteps / BurnSpeed;
        // A gap too short for the switch-off's line and the next burst's goes without the switch-off (the burst has ended
        // the run by itself): what remains is that the next burst's line follows the last one's on the wire, across a run
        // and a gap, two pixels at the least.
        var pulses = longestRunMicrosteps < 0 ? LongestBurstPulses : PulsesWithin(longestRunMicrosteps / BurnSpeed);
        // Never shorter than FREQ's switching needed: shorter pixels have not been shown to keep their edges on the twin.
        var frequencyLine = Format(_profile.Gate.FrequencyCommand, FrequencyHz).Length + _profile.Gate.LineTerminator.Length;
        var floor = (frequencyLine * _gateByteSeconds) + (2 * GateJitterSeconds) + ReactionSeconds - (2 * EdgeGuardSeconds);
        var needed = Math.Max(Math.Max(MinOnSeconds, floor), ((BurstCommand(Math.Max(1, pulses)).Length * _gateByteSeconds) + (2 * GateJitterSeconds) + ReactionSeconds) / 2);
        if (seconds >= needed)
        {
            return null;
        }

        var pixelUm = pixelMicrosteps * MicrostepUm;
        var slowest = Units.UmToMm(pixelUm) / needed;
        return string.Create(
            CultureInfo.InvariantCulture,
            $"at a pitch of {pitchUm:0.###} µm a pixel lasts {Units.SecondsToMs(seconds):0.#} ms at the burn speed, shorter than the {Units.SecondsToMs(needed):0.#} ms the laser gate needs to switch it exactly: burn at {slowest:0.###} mm/s or slower, or use a coarser pitch");
    }

    /// <summary>The built-in model for a process on a profile at the geometry's microstep.</summary>
    public static TimedSwitching For(ProcessSettings process, MachineProfile profile, double microstepUm) => new(process, profile, microstepUm);

    /// <summary>A stroke's motion: from rest to rest at the burn speed.</summary>
    public TrapezoidProfile Stroke(long lengthMicrosteps) => new(lengthMicrosteps, BurnSpeed, Acceleration);

    /// <summary>One axis' travel from rest to rest at the travel speed.</summary>
    public TrapezoidProfile Travel(long lengthMicrosteps) => new(lengthMicrosteps, TravelSpeed, Acceleration);

    /// <summary>
    /// From the first move's arrival to the end of a travel on one or both axes: the longer axis is sent first, the
    /// other one frame later.
    /// </summary>
    public double TravelSeconds(long dx, long dy)
    {
        var x = dx == 0 ? 0 : Travel(dx).Duration;
        var y = dy == 0 ? 0 : Travel(dy).Duration;
        return dx != 0 && dy != 0 ? Math.Max(Math.Max(x, y), Math.Min(x, y) + FrameSeconds) : Math.Max(x, y);
    }

    /// <summary>
    /// Whether the speed of the next motion can be set while the one before brakes (so it costs no time): the new speed is
    /// not below the speed the axis brakes through, for long enough to send the command before the next move.
    /// </summary>
    /// <param name="peakSpeed">Peak speed of the motion before, microsteps/s.</param>
    /// <param name="newSpeed">The speed to set, microsteps/s.</param>
    public bool CanSetSpeedWhileBraking(double peakSpeed, double newSpeed) =>
        Math.Min(peakSpeed, newSpeed) / Acceleration >= FrameSeconds + (4 * StageJitterSeconds) + ReactionSeconds;

    /// <summary>
    /// From a switch-off's nominal time to the earliest arrival of a travel command: no travel is sent before the gate has
    /// acknowledged the switch-off.
    /// </summary>
    public double AfterOffSeconds => OffAcknowledgedSeconds + StageCommandSeconds;

    /// <summary>From a switch-off's nominal time to its acknowledgement at the latest.</summary>
    public double OffAcknowledgedSeconds => OffRoundTripSeconds - OffLeadSeconds + (2 * GateJitterSeconds) + ReactionSeconds;

    /// <summary>What a speed change between two motions adds, when it cannot be made while the first brakes.</summary>
    public double SpeedChangeSeconds => FrameSeconds + MarginSeconds;

    /// <summary>Time from crossing one run's exit edge to crossing the next run's entry edge through a stop-go travel of the X axis.</summary>
    public double StopGoSeconds(long gapMicrosteps)
    {
        var travel = gapMicrosteps - RunOutMicrosteps - RunUpMicrosteps;
        if (travel <= 0)
        {
            return double.PositiveInfinity;
        }

        var brake = Stroke(2 * RunOutMicrosteps);
        var profile = Travel(travel);
        var seconds = (brake.Duration / 2) + MarginSeconds + profile.Duration + MarginSeconds + FirstEdgeSeconds;
        seconds += CanSetSpeedWhileBraking(BurnSpeed, TravelSpeed) ? 0 : SpeedChangeSeconds;
        seconds += CanSetSpeedWhileBraking(profile.PeakSpeed, BurnSpeed) ? 0 : SpeedChangeSeconds;
        return seconds;
    }

    /// <summary>
    /// What a run adds before its engraving, as the executor does it: the gate's preflight (identify, off, watchdog), both
    /// axes identified, homed from the far end of their travel (as after power-up) at the travel speed and the process'
    /// acceleration, their positions read, and the travel with the laser off to the plan's first position.
    /// </summary>
    /// <param name="firstX">The plan's first position, X microsteps.</param>
    /// <param name="firstY">The plan's first position, Y microsteps.</param>
    /// <param name="home">Whether the run homes (the first pass) or starts where the stage stands (a later pass).</param>
    /// <param name="from">Where the stage stands when the run does not home, microsteps.</param>
    public double PreparationSeconds(long firstX, long firstY, bool home = true, (long X, long Y) from = default)
    {
        var gate = _profile.Gate;
        double GateExchange(int commandBytes, int replyBytes) =>
            (2 * _gateAdapterSeconds) + _gateProcessingSeconds + ((commandBytes + replyBytes) * _gateByteSeconds);
        var terminator = gate.LineTerminator.Length;
        var gateSeconds = GateExchange(gate.IdentifyCommand.Length + terminator, 24)
            + GateExchange(OffCommand.Length, gate.AckPrefix.Length + 1 + gate.OffReply.Length + terminator)
            + GateExchange(gate.WatchdogCommand.Length + 3 + terminator, gate.AckPrefix.Length + 1 + gate.WatchdogReply.Length + 3 + terminator);

        // Per axis: device ID, firmware, Device Mode, target speed, acceleration, Maximum Position, home speed, position;
        // then acceleration and home speed set; after homing the position again.
        var roundTrip = StageCommandSeconds + StageReplySeconds;
        if (!home)
        {
            // No acceleration and home speed set, no homing: the travel from where the stage stands.
            var dx = Math.Abs(firstX - from.X);
            var dy = Math.Abs(firstY - from.Y);
            var back = Math.Max(dx == 0 ? 0 : Travel(dx).Duration, dy == 0 ? 0 : Travel(dy).Duration) + roundTrip;
            return gateSeconds + (2 * 9 * roundTrip) + back;
        }

        var stageSeconds = 2 * 11 * roundTrip;
        var homing = Math.Max(Travel(_profile.X.TravelMicrosteps).Duration, Travel(_profile.Y.TravelMicrosteps).Duration) + roundTrip;
        var first = Math.Max(firstX == 0 ? 0 : Travel(firstX).Duration, firstY == 0 ? 0 : Travel(firstY).Duration) + roundTrip;
        return gateSeconds + stageSeconds + homing + first;
    }

    /// <summary>Whether a gap between two runs of a row is crossed at the burn speed (faster than stopping and travelling).</summary>
    public bool CrossesGap(long gapMicrosteps) => _crossesGap.Get(gapMicrosteps);

    /// <summary>Time from one run's exit edge to the next one's entry edge when the gap is crossed without stopping: flown if it can be, else at the burn speed.</summary>
    public double CrossSeconds(long gapMicrosteps) => (gapMicrosteps - (Fly(gapMicrosteps)?.GainMicrosteps ?? 0)) / BurnSpeed;

    /// <summary>A stroke of <paramref name="lengthMicrosteps"/> whose crossed gaps (exit and entry edges, microsteps from its start) are flown where they can be.</summary>
    public StrokePlan Stroke(long lengthMicrosteps, IReadOnlyList<(long Exit, long Entry)> gaps) => new(this, lengthMicrosteps, gaps);

    /// <summary>What a speed bump held <paramref name="holdSeconds"/> gains on the burn speed, microsteps (<see cref="Fly"/>).</summary>
    public double FlyGain(double holdSeconds)
    {
        var hold = Math.Max(0, holdSeconds);
        return hold * Math.Min(Acceleration * hold, Math.Max(0, TravelSpeed - BurnSpeed));
    }

    /// <summary>
    /// How a gap crossed within a stroke is flown, or null when it is too short to gain anything: the target speed goes up
    /// to the travel speed just after the exit edge and back to the burn speed in time for a position query to find the
    /// stage at the burn speed and its reply to be in before the next switch-on must leave.
    /// </summary>
    /// <remarks>
    /// A bump held <c>T</c> (from the speed-up arriving to the speed-down arriving) rises by <c>dV = min(a T, v_t - v_b)</c>
    /// and gains <c>A = T dV</c> on the burn speed. Its latencies (each command arrives within the stage's jitter <c>J</c>)
    /// move the stage by up to <c>A'(T) 2 J</c>; the query, sent once the stage is surely back at the burn speed, measures
    /// that, and the switchings after it are re-timed, so the edges keep the accuracy of a stroke's start. The gap must hold
    /// <c>v_b (2J + T + query delay + reply and switch-on lead + error / v_b) + A</c>; the longest <c>T</c> that fits is taken.
    /// </remarks>
    public FlyingGap? Fly(long gapMicrosteps) => _flown.Get(gapMicrosteps)?.Fly;

    /// <summary><see cref="Fly"/> with what a stroke's check against the device's ramp needs of the gap.</summary>
    internal FlownGap? Flown(long gapMicrosteps) => _flown.Get(gapMicrosteps);

    /// <summary><see cref="Fly"/> worked out afresh, not remembered (the tests' reference).</summary>
    internal FlyingGap? ComputeFly(long gapMicrosteps)
    {
        var rise = TravelSpeed - BurnSpeed;
        if (rise <= 0 || gapMicrosteps <= 0)
        {
            return null;
        }

        var a = Acceleration;
        var j = StageJitterSeconds;
        double Rise(double hold) => Math.Min(a * hold, rise);
        double Slope(double hold) => a * hold < rise ? 2 * a * hold : rise;
        double QueryDelay(double hold) => Math.Max((Rise(hold) / a) + (2 * j), FrameSeconds);
        double MaxError(double hold) => (Slope(hold) * 2 * j) + (2 * BurnSpeed * j) + 1;
        double Needed(double hold)
        {
            // Query reply in, the switch-on's lead, and room for a correction of the largest error.
            var afterQuery = (2 * j) + StageReplySeconds + ReactionSeconds + OnLeadSeconds + ScheduledExtraSeconds + GateJitterSeconds + (MaxError(hold) / BurnSpeed);
            return (BurnSpeed * ((2 * j) + hold + QueryDelay(hold) + afterQuery)) + FlyGain(hold);
        }

        // The speed-down follows the speed-up on the wire, a frame later at the soonest.
        var low = FrameSeconds;
        if (Needed(low) > gapMicrosteps)
        {
            return null;
        }

        var high = low;
        while (Needed(high * 2) <= gapMicrosteps)
        {
            high *= 2;
        }

        high *= 2;
        for (var i = 0; i < 60; i++)
        {
            var mid = 0.5 * (low + high);
            (low, high) = Needed(mid) <= gapMicrosteps ? (mid, high) : (low, mid);
        }

        return new FlyingGap(2 * j, low, QueryDelay(low), FlyGain(low), MaxError(low));
    }

    private static string Format(string format, int value) => string.Format(CultureInfo.InvariantCulture, format, value);
}

/// <summary>A scheduled switch-on as written: its pulses, its delay after the line's last byte (µs), the line's bytes and when that byte is expected at the gate (run seconds).</summary>
public readonly record struct ScheduledBurst(int Pulses, int AfterUs, int LineBytes, double ArrivalSeconds);
