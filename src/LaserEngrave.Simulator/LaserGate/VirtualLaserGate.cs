using System.Globalization;
using System.Text;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Faults;
using LaserEngrave.Simulator.Serial;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Simulator.LaserGate;

/// <summary>The simulated PIC laser gate, speaking docs/laser-gate-protocol.md (with the profile's command strings).</summary>
/// <remarks>
/// <para>
/// Two kinds: the counted-burst gate of the protocol (the default), and the frequency-only gate a lab already has
/// (<see cref="LaserGateKind.FrequencyOnly"/>): it fires at the last frequency set until told otherwise, knows only its
/// frequency command, its off and (when it has one) its identify command, has no watchdog, and answers nothing at all
/// when the profile says it never replies.
/// </para>
/// A command takes effect when its line's last byte has arrived; the reply then takes its own time on the wire.
/// Every line received, valid or not, feeds the watchdog; a Silent fault stops the gate hearing lines, so its
/// watchdog then switches the laser off, as a hung PIC's hardware watchdog would. The watchdog measures the host's
/// silence on the host's clock (the wall clock when attached to ports in virtual time).
/// </remarks>
public sealed class VirtualLaserGate
{
    /// <summary>Highest frequency accepted, Hz.</summary>
    public const int MaxFrequencyHz = 100_000;

    /// <summary>Longest line kept; a longer one is answered as unknown.</summary>
    public const int MaxLineLength = 128;

    /// <summary>Longest delay of a scheduled burst (BURST n hz AFTER us), µs.</summary>
    public const int MaxAfterUs = 1_000_000;

    private readonly LaserGateProfile _profile;
    private readonly SimulatorOptions _options;
    private readonly SimulationClock _clock;
    private readonly FaultInjector _faults;
    private readonly BurnRecorder _recorder;
    private readonly GateCommandSet _commands;
    private readonly Lock _lock = new();
    private readonly List<byte> _line = [];
    private bool _overflow;
    private double _lastHeard;
    private long _generation;
    private ITimer? _watchdog;
    private ITimer? _burstEnd;
    private ITimer? _scheduledStart;

    // The frequency of a scheduled burst accepted and waiting for its first pulse (0: none): STATE? says ON, the watchdog watches.
    private int _armedHz;
    private readonly HashSet<ITimer> _pending = [];
    private double _executeAfter;
    private LinkSession? _session;
    private Action<string> _log = _ => { };

    internal VirtualLaserGate(LaserGateProfile profile, SimulatorOptions options, SimulationClock clock, FaultInjector faults, BurnRecorder recorder)
    {
        _profile = profile;
        _options = options;
        _clock = clock;
        _faults = faults;
        _recorder = recorder;
        _commands = new GateCommandSet(profile);
        Kind = options.GateKind ?? profile.Kind;
        WatchdogMs = Kind == LaserGateKind.FrequencyOnly ? 0 : options.GateWatchdogMs ?? profile.WatchdogMs;
        BaudRate = profile.BaudRate;
    }

    public int BaudRate { get; }

    /// <summary>What kind of gate this is: the counted-burst gate with a watchdog, or a frequency-only one.</summary>
    public LaserGateKind Kind { get; }

    // A frequency-only gate that never answers (the profile's choice) stays silent whatever it hears.
    private bool Silent => Kind == LaserGateKind.FrequencyOnly && _profile.NeverReplies;

    /// <summary>Frequency the laser fires at now, Hz (0 = off).</summary>
    public int FrequencyHz { get; private set; }

    public bool IsFiring => FrequencyHz > 0;

    /// <summary>Watchdog time, ms (0 = disabled).</summary>
    public int WatchdogMs { get; private set; }

    /// <summary>How many times the watchdog has switched the laser off.</summary>
    public int WatchdogTrips { get; private set; }

    /// <summary>Whether the watchdog tripped since the last STATE? query.</summary>
    public bool Tripped { get; private set; }

    /// <summary>Serves <paramref name="link"/> until it closes, the token is cancelled, or a Disconnect fault strikes.</summary>
    internal async Task RunAsync(ISerialLink link, Action<string> log, LinkLatency latency, CancellationToken cancellationToken)
    {
        var session = new LinkSession(link, _clock, BaudRate, _options.BitsPerByte, latency, log);
        lock (_lock)
        {
            _session = session;
            _log = log;
            _line.Clear();
            _overflow = false;
        }

        try
        {
            await session.RunAsync(OnByte, cancellationToken);
        }
        finally
        {
            lock (_lock)
            {
                if (_session == session)
                {
                    _session = null;
                }
            }
        }
    }

    private Action? OnByte(byte value, double arrivedAt, double gapSeconds)
    {
        lock (_lock)
        {
            if (value != (byte)'\n')
            {
                if (_line.Count < MaxLineLength)
                {
                    _line.Add(value);
                }
                else
                {
                    _overflow = true;
                }

                return null;
            }

            var line = _overflow ? "\u0000" : Encoding.ASCII.GetString([.. _line]).TrimEnd('\r').Trim();
            var lineBytes = _line.Count + 1;
            _line.Clear();
            _overflow = false;
            if (_options.GateProcessing is not null)
            {
                // A drawn processing time (a gate of another make): the link runs the action that much later.
                return () => Execute(line, arrivedAt);
            }

            return () => ExecuteAsTheFirmware(line, lineBytes, arrivedAt);
        }
    }

    // The reference firmware's own time for this line (GateFirmwareTiming): the link hands the line over as its last
    // byte arrives, and the gate acts when the firmware would have. Lines keep their order (a line takes milliseconds to
    // arrive, the firmware well under one to act, so a later line never overtakes).
    private void ExecuteAsTheFirmware(string line, int lineBytes, double arrivedAt)
    {
        lock (_lock)
        {
            var at = Math.Max(_clock.NowSeconds + FirmwareProcessingSeconds(_commands, line, lineBytes), _executeAfter);
            _executeAfter = at;
            ITimer? timer = null;
            timer = _clock.At(at, () =>
            {
                lock (_lock)
                {
                    _pending.Remove(timer!);
                }

                Execute(line, arrivedAt);
            });
            _pending.Add(timer);
        }
    }

    /// <summary>
    /// The reference firmware's time from a line's last byte to its effect and reply (<see cref="GateFirmwareTiming"/>),
    /// for the line as <paramref name="commands"/> reads it: the one place the twin and a replay's round trips take it from.
    /// </summary>
    internal static double FirmwareProcessingSeconds(GateCommandSet commands, string line, int lineBytes)
    {
        var command = commands.Match(line, out var args);
        var fires = command switch
        {
            GateCommand.Frequency => TryNumber(args[0], out var hz) && hz is > 0 and <= MaxFrequencyHz,
            GateCommand.Burst => TryNumber(args[0], out var n) && TryNumber(args[1], out var bhz) && n is >= 1 and <= 1_000_000 && bhz is >= 1 and <= MaxFrequencyHz,

            // A scheduled burst is accepted (and answered) when the train is stopped; its first pulse is timed apart.
            _ => false,
        };
        return GateFirmwareTiming.ProcessingSeconds(command, lineBytes, fires);
    }

    private void Execute(string line, double arrivedAt)
    {
        bool disconnect;
        lock (_lock)
        {
            var now = _clock.NowSeconds;
            var fault = _faults.OnCommand(FaultTarget.Gate);
            disconnect = fault.Disconnect;
            if (!fault.Ignore && !fault.Disconnect)
            {
                _lastHeard = _clock.NowSeconds;
                ArmWatchdog();
                if (fault.RefuseCode is { } code)
                {
                    // A gate that never replies cannot say it refused: the command is simply not carried out.
                    if (!Silent)
                    {
                        Reply($"{_profile.ErrorPrefix} {code.ToString(CultureInfo.InvariantCulture)} INJECTED");
                    }
                }
                else if (line.Length > 0)
                {
                    var reply = Run(line, now, arrivedAt);
                    if (!Silent)
                    {
                        Reply(reply);
                    }
                }
            }
        }

        if (disconnect)
        {
            _session?.Close("disconnected by an injected fault");
        }
    }

    private string Run(string line, double now, double arrivedAt)
    {
        var ok = _profile.AckPrefix;
        var command = _commands.Match(line, out var args);
        if (Kind == LaserGateKind.FrequencyOnly && command is GateCommand.State or GateCommand.KeepAlive or GateCommand.Watchdog or GateCommand.Burst)
        {
            // The lab's PIC knows FREQ and its off, nothing of the counted-burst protocol.
            command = GateCommand.Unknown;
        }

        if (!_options.GateScheduledBursts && command is GateCommand.Capabilities)
        {
            // An older gate: it does not know the question, and refuses the scheduled burst's fourth word (below).
            command = GateCommand.Unknown;
        }

        switch (command)
        {
            case GateCommand.Identify:
                return $"{ok} PICGATE {_options.GateFirmware}";
            case GateCommand.Frequency:
                if (!TryNumber(args[0], out var hz))
                {
                    return Syntax();
                }

                if (hz is < 0 or > MaxFrequencyHz)
                {
                    return Range();
                }

                SetFrequency(hz, now);
                return Ack(_profile.FrequencyReply, hz);
            case GateCommand.Off:
                SetFrequency(0, now);
                return Ack(_profile.OffReply);
            case GateCommand.State:
                var state = $"{ok} STATE {(IsFiring ? FrequencyHz : _armedHz)} {(IsFiring || _armedHz > 0 ? "ON" : "OFF")} WDOG {WatchdogMs}{(Tripped ? " TRIPPED" : string.Empty)}";
                Tripped = false;
                return state;
            case GateCommand.KeepAlive:
                return Ack(_profile.KeepAliveReply);
            case GateCommand.Watchdog:
                if (!TryNumber(args[0], out var ms))
                {
                    return Syntax();
                }

                if (ms != 0 && ms is < 50 or > 60_000)
                {
                    return Range();
                }

                WatchdogMs = ms;
                ArmWatchdog();
                return Ack(_profile.WatchdogReply, ms);
            case GateCommand.Burst:
                if (!TryNumber(args[0], out var pulses) || !TryNumber(args[1], out var burstHz))
                {
                    return Syntax();
                }

                if (pulses is < 1 or > 1_000_000 || burstHz is < 1 or > MaxFrequencyHz)
                {
                    return Range();
                }

                StartBurst(pulses, burstHz, now);
                return Ack(_profile.BurstReply, pulses, burstHz);
            case GateCommand.BurstAfter when !_options.GateScheduledBursts:
                return Syntax();
            case GateCommand.BurstAfter:
                if (!TryNumber(args[0], out var afterPulses) || !TryNumber(args[1], out var afterHz) || !TryNumber(args[2], out var afterUs))
                {
                    return Syntax();
                }

                if (afterPulses is < 1 or > 1_000_000 || afterHz is < 1 or > MaxFrequencyHz || afterUs is < 0 or > MaxAfterUs)
                {
                    return Range();
                }

                ScheduleBurst(afterPulses, afterHz, afterUs, now, arrivedAt);
                return Ack(_profile.BurstAfterReply, afterPulses, afterHz, afterUs);
            case GateCommand.Capabilities:
                return $"{ok} {_profile.CapabilitiesReply} AFTER";
            case GateCommand.Malformed:
                return Syntax();
            default:
                return $"{_profile.ErrorPrefix} 1 UNKNOWN";
        }

        string Ack(string format, params object[] values) => $"{ok} {string.Format(CultureInfo.InvariantCulture, format, values)}";

        string Syntax() => $"{_profile.ErrorPrefix} 3 SYNTAX";

        string Range() => $"{_profile.ErrorPrefix} 2 RANGE";
    }

    // Caller holds _lock. Fires pulses at hz from now, counted: the burst ends exactly N fired periods after it began (the
    // firmware's period grid), though the clock's timer, rounded up to whole ticks, runs a moment later (which would let
    // an (N+1)th pulse through).
    private void StartBurst(int pulses, int hz, double now)
    {
        SetFrequency(hz, now);
        var generation = _generation;
        var end = now + (pulses * GateFirmwareTiming.FiredPeriodSeconds(hz));
        _burstEnd = _clock.At(end, () =>
        {
            lock (_lock)
            {
                if (generation == _generation)
                {
                    SetFrequency(0, end);
                }
            }
        });
    }

    // Caller holds _lock. The reference firmware's scheduled burst: accepted now (the train under way stopped, the reply
    // leaving), its first pulse afterUs after the line's last byte arrived, on the gate's own timer (simavr: within
    // +0.44 µs of that, docs/gate-firmware.md), or, when that is sooner than the gate can start a train, as soon as it can
    // (GateFirmwareTiming.StartCycles after the line is processed). Any later frequency command or the watchdog cancels it.
    private void ScheduleBurst(int pulses, int hz, int afterUs, double now, double arrivedAt)
    {
        SetFrequency(0, now);
        _armedHz = hz;
        var generation = _generation;
        var start = Math.Max(arrivedAt + (afterUs / 1e6), now + (GateFirmwareTiming.StartCycles / GateFirmwareTiming.ClockHz));
        _scheduledStart = _clock.At(start, () =>
        {
            lock (_lock)
            {
                if (generation == _generation)
                {
                    StartBurst(pulses, hz, start);
                }
            }
        });
        ArmWatchdog();
    }

    private static bool TryNumber(string text, out int value) =>
        int.TryParse(text, NumberStyles.AllowLeadingSign, CultureInfo.InvariantCulture, out value);

    // Caller holds _lock. Any frequency change ends a burst in progress. The pulse train is the firmware's: at the
    // period its timer can fire (GateFirmwareTiming), and started afresh by every frequency command while it fires
    // (the firmware stops its timer and starts it again, the first pulse at once), so the recorder sees the old train
    // end and a new one begin at this instant.
    private void SetFrequency(int hz, double now)
    {
        _generation++;
        _burstEnd?.Dispose();
        _burstEnd = null;
        _scheduledStart?.Dispose();
        _scheduledStart = null;
        _armedHz = 0;
        if (IsFiring && hz > 0)
        {
            _recorder.RecordLaser(now, 0);
        }

        FrequencyHz = hz;
        _recorder.RecordLaser(now, GateFirmwareTiming.FiredHz(hz));
        ArmWatchdog();
    }

    // Caller holds _lock. (Re)starts the watchdog from the last line heard while the laser fires; it measures the host's
    // silence, so it runs on the host's clock.
    private void ArmWatchdog()
    {
        _watchdog?.Dispose();
        _watchdog = null;
        if ((!IsFiring && _armedHz == 0) || WatchdogMs <= 0)
        {
            return;
        }

        var generation = _generation;
        var heard = _lastHeard;
        _watchdog = _clock.At(heard + Units.MsToSeconds(WatchdogMs), () =>
        {
            lock (_lock)
            {
                if (generation != _generation || heard != _lastHeard || (!IsFiring && _armedHz == 0))
                {
                    return;
                }

                // Counted before the laser stops: whoever sees it stopped (without the lock) also sees why.
                Tripped = true;
                WatchdogTrips++;
                SetFrequency(0, _clock.NowSeconds);
                _log($"watchdog switched the laser off after {WatchdogMs} ms without a line");
            }
        });
    }

    private void Reply(string text)
    {
        var fault = _faults.OnReply(FaultTarget.Gate);
        if (fault.Drop)
        {
            return;
        }

        var bytes = Encoding.ASCII.GetBytes(text + _profile.LineTerminator);
        if (fault.CorruptByte is int index && index < bytes.Length)
        {
            bytes[index] ^= 0xFF;
        }

        _session?.Send(bytes, fault.Delay);
    }
}
