using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Simulator;

/// <summary>How the simulated machine behaves where the hardware leaves a choice or the documentation is silent.</summary>
public sealed record SimulatorOptions
{
    /// <summary>
    /// The twin the front ends start from (the CLI's <c>--simulate</c> and <c>simulator</c>, the app's in-process
    /// simulator): a host as late as a lab PC with other work on it (<see cref="Timing.HostLateness.Realistic"/>: late
    /// wake-ups, rare stalled writes and late reads) and replies now and then in two pieces
    /// (<see cref="Serial.ReplyPieces.Realistic"/>), so that what a user sees does not flatter the host; an options file's
    /// <c>hostLateness</c> and <c>replyPieces</c> override them (zeros: never late, always whole).
    /// </summary>
    public static SimulatorOptions FrontEnd { get; } = new() { HostLateness = HostLateness.Realistic, ReplyPieces = Serial.ReplyPieces.Realistic };

    /// <summary>Run on the wall clock (<see cref="TimeProvider.System"/>) instead of virtual time, e.g. for the app's live view.</summary>
    /// <remarks>A simulator attached to ports always runs on the wall clock: its host lives in real time in another process.</remarks>
    public bool RealTime { get; init; }

    /// <summary>
    /// Virtual time that never runs ahead of the wall clock: the run takes its real time, as the app's live view needs,
    /// but every event still happens at its exact virtual time (the wall clock's timers would be late by a scheduler
    /// tick). In-process only; <see cref="RealTime"/> wins if both are set.
    /// </summary>
    public bool Paced { get; init; }

    /// <summary>Wall-clock time at which virtual time starts (what logs show as a run's start); now when not given.</summary>
    public DateTimeOffset? VirtualStart { get; init; }

    /// <summary>Seed of every random draw of the simulation (latency jitter): same seed, same run.</summary>
    public int Seed { get; init; } = 1;

    /// <summary>Latency of each USB-serial adapter, per transfer and direction, on top of the wire time.</summary>
    public Jitter AdapterLatency { get; init; } = new(1.0, 0.5);

    /// <summary>
    /// How late the host's code wakes from each timed wait (in-process, virtual time only): a computer busy with other
    /// work. <see cref="Timing.HostLateness.Realistic"/> is a lab PC with other work on it, what the front ends start
    /// from (<see cref="FrontEnd"/>).
    /// </summary>
    /// <remarks>
    /// None here, so that the library's own tests of the protocol (a single executor, which stops at its first switch-on
    /// later than the edge tolerance) measure the protocol alone.
    /// </remarks>
    public HostLateness HostLateness { get; init; } = HostLateness.None;

    /// <summary>
    /// How the USB-serial adapters deliver replies: some in two pieces a few milliseconds apart (in-process and attached
    /// to ports alike). None here; the front ends' default (<see cref="FrontEnd"/>) has <see cref="Serial.ReplyPieces.Realistic"/>.
    /// </summary>
    public Serial.ReplyPieces ReplyPieces { get; init; }

    /// <summary>The laser gate's time from a command's last byte to the Q-switch changing (and its reply leaving), drawn per command.</summary>
    /// <remarks>
    /// Null (the default): the reference firmware's own time for each line, as measured in simavr
    /// (<see cref="LaserGate.GateFirmwareTiming"/>, docs/gate-firmware.md): 51 µs for OFF, 185 µs to the first pulse of
    /// a 15-byte BURST. A value: a draw from that range for every command, for a gate of another make.
    /// </remarks>
    public Jitter? GateProcessing { get; init; }

    /// <summary>
    /// Where both axes stand at power-up, mm from home (clamped to their travel); null: the far end of the travel, as a
    /// T-series device reports after power-up. Tests on the wall clock start near home so homing takes little time.
    /// </summary>
    public double? StartMm { get; init; }

    /// <summary>Where each axis (X, Y, then Z) starts, in microsteps, over <see cref="StartMm"/>: a replay's start, as the recorded devices reported it. Not in the options file.</summary>
    public IReadOnlyList<long>? StartMicrosteps { get; init; }

    /// <summary>Faults to inject from the start, in the grammar of <see cref="Faults.FaultInjector.Parse"/>.</summary>
    public string? FaultSpec { get; init; }

    /// <summary>Bits per byte on the wire: 8 data bits, no parity, 1 stop bit, plus the start bit.</summary>
    public int BitsPerByte { get; init; } = (int)SerialLine.BitsPerByte;

    /// <summary>A partial Zaber frame is dropped when the next byte comes later than this after the previous one.</summary>
    public TimeSpan PartialFrameTimeout { get; init; } = TimeSpan.FromMilliseconds(10);

    /// <summary>
    /// Firmware version of both axes (523 = 5.23), answered to Return Firmware Version; the devices refuse what that firmware
    /// lacks, as the manual says: below 5.20 no Set Home Speed (Home runs at the Target Speed), below 5.04 no Echo Data,
    /// 5.21-5.22 refuse Target Speed 0 and a Maximum Position below the current position (docs/zaber-protocol.md).
    /// </summary>
    public int FirmwareVersion { get; init; } = 523;

    /// <summary>Device type ID answered to Return Device ID.</summary>
    /// <remarks>The real T-LA60A ID is not documented in the sources we have; this is a stand-in the host only displays.</remarks>
    public int DeviceId { get; init; } = 4212;

    /// <summary>Target Speed data at power-up (x 9.375 microsteps/s; 2000 = 1.74 mm/s on a T-LA).</summary>
    public int TargetSpeedData { get; init; } = 2000;

    /// <summary>Home Speed data at power-up.</summary>
    public int HomeSpeedData { get; init; } = 2000;

    /// <summary>Acceleration data at power-up (x 11250 microsteps/s²; 10 = 11 mm/s² on a T-LA).</summary>
    public int AccelerationData { get; init; } = 10;

    /// <summary>Device Mode at power-up (0: auto-reply on, move tracking off).</summary>
    public int DeviceMode { get; init; }

    /// <summary>Interval of Move Tracking replies (command 8) while Device Mode bit 4 is set.</summary>
    public TimeSpan MoveTrackingPeriod { get; init; } = TimeSpan.FromMilliseconds(250);

    /// <summary>How long a Renumber takes before the device replies ("less than a second").</summary>
    public TimeSpan RenumberTime { get; init; } = TimeSpan.FromMilliseconds(500);

    /// <summary>
    /// Whether a move that another move pre-empts still replies (with the position where it was pre-empted).
    /// Undocumented for T-series; off by default because Zaber's own libraries expect one reply per command.
    /// </summary>
    public bool ReplyToPreemptedMoves { get; init; }

    /// <summary>Firmware text of the laser gate's identification reply.</summary>
    public string GateFirmware { get; init; } = "SIM-1.0";

    /// <summary>
    /// Whether the twin's gate takes scheduled bursts (`BURST n hz AFTER us`, and lists AFTER in its `CAPS?` reply), as the
    /// reference firmware AVR-1.1; false: an older gate (AVR-1.0, the PIC16F628A) that answers `CAPS?` with `ERR 1 UNKNOWN`
    /// and a scheduled burst with `ERR 3 SYNTAX`, and is sent plain bursts.
    /// </summary>
    public bool GateScheduledBursts { get; init; } = true;

    /// <summary>Watchdog time of the gate at power-up, ms; null takes the machine profile's.</summary>
    public int? GateWatchdogMs { get; init; }

    /// <summary>
    /// What kind of gate the twin is; null takes the machine profile's (<c>gate.kind</c>). Set apart from the profile, the
    /// twin is a gate the profile does not describe, which commissioning must notice.
    /// </summary>
    public LaserGateKind? GateKind { get; init; }

    /// <summary>Laser-on intervals with both axes still shorter than this are not counted as dwell.</summary>
    /// <remarks>
    /// With completion-based replies the laser unavoidably stands still at both ends of every burn run: at the start
    /// for the gate's acknowledgement and the move command (13.5 + 6.25 ms at 9600 baud for "OK FREQ 1000"), at the
    /// end for the move's reply and the OFF line (6.25 + 4.2 ms). A speed change between switching the laser on and
    /// the move adds 12.5 ms and goes over the default.
    /// </remarks>
    public TimeSpan DwellTolerance { get; init; } = TimeSpan.FromMilliseconds(25);

    /// <summary>Where the beam is truly in focus, µm from the profile's visible focus (z.focusMm): the focal offset seed 002 finds with a focal series.</summary>
    public double TrueFocusOffsetUm { get; init; }

    /// <summary>The beam's Rayleigh length zR, µm: the spot grows as d0 √(1 + (Δz / zR)²) away from the true focus; null: spot growth not modelled.</summary>
    public double? RayleighLengthUm { get; init; }
}
