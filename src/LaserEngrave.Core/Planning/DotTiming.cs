using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Motion;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Core.Planning;

/// <summary>
/// The timing model of dot mode (<see cref="PlanMode.Dots"/>): what each step, each burst and the wait after it take, as
/// the executor (Devices/Execution/RunExecutor.Dots.cs) does them one after the other. All times are seconds.
/// </summary>
/// <remarks>
/// <para>
/// At each dot the executor sends Move Absolute (X, and Y at a row change) at the travel speed and waits for every reply,
/// lets the stage settle (<see cref="ProcessSettings.DotSettleMs"/>), sends `BURST n f` and waits for `OK BURST n`, then
/// waits until the burst has surely ended before the next move. As in <see cref="TimedSwitching"/>, a command acts when
/// its last byte has arrived: the adapter's latency (the profile's <c>latency</c> section) plus its bytes at 10 bits
/// each, plus the gate's processing for a gate command; the gate answers as the burst starts.
/// </para>
/// <para>
/// The burst started at the latest the reply's bytes and the gate adapter's least latency before the reply arrived, so
/// the laser is surely off <see cref="AfterAckSeconds"/> after the acknowledgement: N / f, less that, plus a reaction
/// margin. Nothing moves before then.
/// </para>
/// </remarks>
public sealed class DotTiming
{

    // Time the host allows itself to react to a reply before acting on it.
    private const double ReactionSeconds = 0.0005;

    public DotTiming(ProcessSettings process, MachineProfile profile, double microstepUm)
    {
        ArgumentNullException.ThrowIfNull(process);
        ArgumentNullException.ThrowIfNull(profile);
        var latency = profile.Latency;
        var gate = profile.Gate;
        PulsesPerDot = process.PulsesPerDot;
        FrequencyHz = process.LaserFrequencyWholeHz;
        TravelSpeedData = StageUnits.SpeedData(process.TravelSpeedMmPerS, microstepUm);
        AccelerationData = StageUnits.AccelerationData(process.AccelerationMmPerS2, microstepUm);
        TravelSpeed = StageUnits.SpeedMicrostepsPerS(TravelSpeedData);
        Acceleration = StageUnits.AccelerationMicrostepsPerS2(AccelerationData);

        var stageByte = SerialLine.BitsPerByte / process.StageBaudRate;
        FrameSeconds = ZaberFrame.Length * stageByte;
        StageAdapterSeconds = Units.MsToSeconds(latency.StageMs);
        StageRoundTripSeconds = (2 * StageAdapterSeconds) + (2 * FrameSeconds);

        var gateByte = SerialLine.BitsPerByte / process.GateBaudRate;
        var gateAdapter = Units.MsToSeconds(latency.GateMs);
        var processing = Units.MsToSeconds(latency.GateProcessingMs);
        BurstCommand = string.Format(CultureInfo.InvariantCulture, gate.BurstCommand, PulsesPerDot, FrequencyHz) + gate.LineTerminator;
        var reply = gate.AckPrefix + " " + string.Format(CultureInfo.InvariantCulture, gate.BurstReply, PulsesPerDot, FrequencyHz) + gate.LineTerminator;
        var replyWire = reply.Length * gateByte;
        BurstSeconds = (double)PulsesPerDot / FrequencyHz;
        BurstLeadSeconds = gateAdapter + (BurstCommand.Length * gateByte) + processing;
        BurstReplySeconds = replyWire + gateAdapter;
        var leastAdapter = Units.MsToSeconds(Math.Max(0, latency.GateMs - latency.GateJitterMs));
        AfterAckSeconds = Math.Max(0, BurstSeconds - replyWire - leastAdapter) + ReactionSeconds;
        SettleSeconds = Units.MsToSeconds(process.DotSettleMs);

        var offReply = gate.AckPrefix + " " + gate.OffReply + gate.LineTerminator;
        OffRoundTripSeconds = (2 * gateAdapter) + processing + ((gate.OffCommand.Length + gate.LineTerminator.Length + offReply.Length) * gateByte);
        WatchdogSeconds = Units.MsToSeconds(gate.WatchdogMs);
    }

    public int PulsesPerDot { get; }

    /// <summary>The burst's frequency as the gate is sent it, whole Hz.</summary>
    public int FrequencyHz { get; }

    public int TravelSpeedData { get; }

    public int AccelerationData { get; }

    /// <summary>Speed of every move between dots, microsteps/s (the travel speed, quantised: the laser never fires while moving).</summary>
    public double TravelSpeed { get; }

    /// <summary>Acceleration, microsteps/s² (quantised).</summary>
    public double Acceleration { get; }

    public double FrameSeconds { get; }

    public double StageAdapterSeconds { get; }

    /// <summary>A stage command and its reply: both frames and both adapter latencies.</summary>
    public double StageRoundTripSeconds { get; }

    /// <summary>The burst command line, terminator included.</summary>
    public string BurstCommand { get; }

    /// <summary>N / f: how long the laser fires at a dot.</summary>
    public double BurstSeconds { get; }

    /// <summary>From writing the burst command to the gate firing.</summary>
    public double BurstLeadSeconds { get; }

    /// <summary>From the gate firing (and answering) to the host having the acknowledgement.</summary>
    public double BurstReplySeconds { get; }

    /// <summary>How long after the acknowledgement the laser is surely off again.</summary>
    public double AfterAckSeconds { get; }

    public double SettleSeconds { get; }

    /// <summary>The switch-off at the end of the run and its acknowledgement.</summary>
    public double OffRoundTripSeconds { get; }

    /// <summary>The gate's watchdog time (0: none).</summary>
    public double WatchdogSeconds { get; }

    /// <summary>The start of a run: acceleration and travel speed set on both axes, one round trip each.</summary>
    public double StartSeconds => 4 * StageRoundTripSeconds;

    /// <summary>At a dot: settle, the burst command, its acknowledgement and the wait for the burst's end.</summary>
    public double AtDotSeconds => SettleSeconds + BurstLeadSeconds + BurstReplySeconds + AfterAckSeconds;

    /// <summary>Null when a burst fits the gate's watchdog; otherwise why not, in one line (the watchdog would cut every burst short).</summary>
    public string? BurstProblem =>
        WatchdogSeconds > 0 && BurstSeconds > WatchdogSeconds / 2
            ? string.Create(CultureInfo.InvariantCulture, $"a burst of {PulsesPerDot} pulses at {FrequencyHz} Hz lasts {Units.SecondsToMs(BurstSeconds):0.###} ms, more than half the gate's watchdog time ({Units.SecondsToMs(WatchdogSeconds):0} ms), which would cut it short; fire fewer pulses per dot or at a higher frequency")
            : null;

    /// <summary>The step from one dot to the next: Move Absolute of each moving axis (X first, Y right behind it on the shared line), the motions, and the replies.</summary>
    /// <param name="dx">The X distance, microsteps.</param>
    /// <param name="dy">The Y distance, microsteps.</param>
    /// <param name="speedData">The Set Target Speed data the axes move at (the travel speed, or the burn speed of a paper plan).</param>
    public double StepSeconds(long dx, long dy, int speedData)
    {
        dx = Math.Abs(dx);
        dy = Math.Abs(dy);
        if (dx == 0 && dy == 0)
        {
            return 0;
        }

        var speed = speedData == TravelSpeedData ? TravelSpeed : StageUnits.SpeedMicrostepsPerS(speedData);
        var x = dx == 0 ? 0 : FrameSeconds + Motion(dx, speed);
        var y = dy == 0 ? 0 : (dx == 0 ? FrameSeconds : 2 * FrameSeconds) + Motion(dy, speed);
        return StageAdapterSeconds + Math.Max(x, y) + FrameSeconds + StageAdapterSeconds;
    }

    private double Motion(long distance, double speed) => new TrapezoidProfile(distance, speed, Acceleration).Duration;
}
