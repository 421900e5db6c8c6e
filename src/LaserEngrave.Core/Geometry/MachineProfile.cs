using System.Text.Json;
using System.Text.Json.Serialization;
using LaserEngrave.Core.IO;

namespace LaserEngrave.Core.Geometry;

/// <summary>One linear axis of the stage: which Zaber device drives it and what it can do.</summary>
public record AxisProfile
{
    /// <summary>Zaber device number on the daisy chain (1 = X, 2 = Y by default).</summary>
    public byte DeviceNumber { get; init; }

    /// <summary>Length of one microstep in µm (T-LA: 0.09921875 µm at 64 microsteps per step).</summary>
    public double MicrostepUm { get; init; } = 0.09921875;

    /// <summary>Travel of the axis in mm.</summary>
    public double TravelMm { get; init; } = 60;

    /// <summary>Highest speed the axis is allowed, mm/s.</summary>
    public double MaxSpeedMmPerS { get; init; } = 4;

    /// <summary>Highest acceleration the axis is allowed, mm/s².</summary>
    public double MaxAccelerationMmPerS2 { get; init; } = 200;

    /// <summary>Travel in whole microsteps (the device's Maximum Position).</summary>
    [JsonIgnore]
    public long TravelMicrosteps => (long)Math.Floor(StageUnits.MmToMicrosteps(TravelMm, MicrostepUm));
}

/// <summary>What kind of laser gate the machine has: what it can do decides how a run switches the laser.</summary>
[JsonConverter(typeof(LaserGateKindConverter))]
public enum LaserGateKind
{
    /// <summary>The gate of docs/laser-gate-protocol.md: counted bursts (BURST), a watchdog (WDOG, PING) and its state (STATE?).</summary>
    CountedBurst,

    /// <summary>A gate that only sets a frequency (FREQ f, FREQ 0): the host times every switch-on and switch-off itself, and nothing stops the laser when the host hangs.</summary>
    FrequencyOnly,
}

/// <summary>Reads and writes <see cref="LaserGateKind"/> as "countedBurst" and "frequencyOnly", never as a number.</summary>
public sealed class LaserGateKindConverter : JsonStringEnumConverter<LaserGateKind>
{
    public LaserGateKindConverter()
        : base(JsonNamingPolicy.CamelCase, allowIntegerValues: false)
    {
    }
}

/// <summary>How the laser gate is spoken to; every string is overridable for a PIC that speaks differently.</summary>
public sealed record LaserGateProfile
{
    /// <summary>
    /// What the gate can do: the counted-burst gate with a watchdog (the default), or a gate that only sets a frequency.
    /// Left out of the file when it is the default, so existing profiles and logs read and write as before.
    /// </summary>
    [JsonIgnore(Condition = JsonIgnoreCondition.WhenWritingDefault)]
    public LaserGateKind Kind { get; init; }

    /// <summary>
    /// A frequency-only gate that never answers a line: each command counts as carried out once written. Only a
    /// frequency-only gate may say so (the counted-burst gate proves itself by its replies).
    /// </summary>
    [JsonIgnore(Condition = JsonIgnoreCondition.WhenWritingDefault)]
    public bool NeverReplies { get; init; }

    /// <summary>Whether this gate counts its bursts and has a watchdog (the default protocol).</summary>
    [JsonIgnore]
    public bool CountsBursts => Kind == LaserGateKind.CountedBurst;

    /// <summary>Whether the gate has a watchdog that switches the laser off when the host falls silent.</summary>
    [JsonIgnore]
    public bool HasWatchdog => WatchdogMs > 0;

    /// <summary>Whether the host identifies the gate (a frequency-only gate may have no identify command, and one that never replies cannot answer it).</summary>
    [JsonIgnore]
    public bool Identifies => !NeverReplies && !string.IsNullOrWhiteSpace(IdentifyCommand);

    /// <summary>
    /// What protects the laser when the computer hangs with a gate that has no watchdog, in one plain sentence: preflight
    /// says it and asks the person to accept it (`--accept-no-watchdog`, the app's checkbox), and the run log keeps it.
    /// </summary>
    public const string NoWatchdogSentence =
        "this laser gate has no watchdog: if this computer hangs while the laser fires, the laser keeps firing, and only the hardware interlock or your hand on the key switch stops it";

    public int BaudRate { get; init; } = 9600;

    public string IdentifyCommand { get; init; } = "*IDN?";

    /// <summary>Sets the Q-switch frequency; {0} is the frequency in whole Hz (0 = off).</summary>
    public string FrequencyCommand { get; init; } = "FREQ {0}";

    public string OffCommand { get; init; } = "OFF";

    public string StatusCommand { get; init; } = "STATE?";

    public string KeepAliveCommand { get; init; } = "PING";

    /// <summary>Sets the watchdog time; {0} is milliseconds (0 = disabled).</summary>
    public string WatchdogCommand { get; init; } = "WDOG {0}";

    /// <summary>Fires a burst; {0} is the pulse count, {1} the frequency in Hz.</summary>
    public string BurstCommand { get; init; } = "BURST {0} {1}";

    /// <summary>
    /// Fires a burst whose first pulse the gate times itself: {0} pulses at {1} Hz, the first {2} µs after the line's last
    /// byte has arrived (docs/laser-gate-protocol.md, "Scheduled bursts"). Only a gate whose <see cref="CapabilitiesCommand"/>
    /// lists AFTER takes it; an older gate refuses it and never fires it.
    /// </summary>
    public string BurstAfterCommand { get; init; } = "BURST {0} {1} AFTER {2}";

    /// <summary>Asks what the gate can do beyond the base protocol (an older gate refuses it).</summary>
    public string CapabilitiesCommand { get; init; } = "CAPS?";

    /// <summary>What acknowledges <see cref="IdentifyCommand"/> after the prefix; empty: any acknowledgement.</summary>
    public string IdentifyReply { get; init; } = string.Empty;

    /// <summary>What acknowledges <see cref="FrequencyCommand"/> after the prefix; {0} as in the command.</summary>
    public string FrequencyReply { get; init; } = "FREQ {0}";

    /// <summary>What acknowledges <see cref="OffCommand"/> after the prefix.</summary>
    public string OffReply { get; init; } = "FREQ 0";

    /// <summary>The first word of the reply to <see cref="StatusCommand"/> after the prefix.</summary>
    public string StatusReply { get; init; } = "STATE";

    /// <summary>What acknowledges <see cref="KeepAliveCommand"/> after the prefix.</summary>
    public string KeepAliveReply { get; init; } = "PONG";

    /// <summary>What acknowledges <see cref="WatchdogCommand"/> after the prefix; {0} as in the command.</summary>
    public string WatchdogReply { get; init; } = "WDOG {0}";

    /// <summary>What acknowledges <see cref="BurstCommand"/> after the prefix; {0} and {1} as in the command.</summary>
    public string BurstReply { get; init; } = "BURST {0}";

    /// <summary>What acknowledges <see cref="BurstAfterCommand"/> after the prefix; {0}, {1} and {2} as in the command.</summary>
    public string BurstAfterReply { get; init; } = "BURST {0} AFTER {2}";

    /// <summary>The first word of the reply to <see cref="CapabilitiesCommand"/> after the prefix; the words after it name what the gate can do.</summary>
    public string CapabilitiesReply { get; init; } = "CAPS";

    /// <summary>Every successful reply starts with this.</summary>
    public string AckPrefix { get; init; } = "OK";

    /// <summary>Every refusal starts with this.</summary>
    public string ErrorPrefix { get; init; } = "ERR";

    public string LineTerminator { get; init; } = "\n";

    /// <summary>How long to wait for an acknowledgement before the gate counts as silent.</summary>
    public int TimeoutMs { get; init; } = 500;

    /// <summary>Watchdog time programmed into the gate: it switches the laser off after this long without a command (50..60000); 0 for a frequency-only gate, which has none.</summary>
    public int WatchdogMs { get; init; } = 1000;

    /// <summary>Highest Q-switch frequency the gate takes, whole Hz (the default protocol's FREQ range is 0..100000).</summary>
    public int MaxFrequencyHz { get; init; } = 100000;
}

/// <summary>The machine's serial latencies besides the wire time, which timed laser switching plans with (`laserengrave machine latency` measures them).</summary>
/// <remarks>
/// Each is a mean and the half-width of its spread, in ms. The defaults are the simulator's (docs/simulator.md): a USB-serial
/// adapter adds 1 ± 0.5 ms to every write and every reply, and the gate takes 0.5 ± 0.2 ms from a command's last byte to
/// the Q-switch changing.
/// </remarks>
public sealed record LatencyProfile
{
    /// <summary>The stage link's adapter latency, one way, ms: from the host's write to the command leaving on the wire, and from a reply's last byte to the host.</summary>
    public double StageMs { get; init; } = 1.0;

    /// <summary>Half-width of the spread of <see cref="StageMs"/>, ms.</summary>
    public double StageJitterMs { get; init; } = 0.5;

    /// <summary>The gate link's adapter latency, one way, ms.</summary>
    public double GateMs { get; init; } = 1.0;

    /// <summary>Half-width of the spread of <see cref="GateMs"/>, ms.</summary>
    public double GateJitterMs { get; init; } = 0.5;

    /// <summary>The gate's processing time from a command's last byte to the Q-switch changing (and its reply leaving), ms.</summary>
    /// <remarks>
    /// The reference firmware's (firmware/gate, docs/gate-firmware.md): a BURST line of 14 to 19 bytes fires its first
    /// pulse 0.180 to 0.214 ms after its last stop bit (measured in simavr). The timed switch-on is planned with it, so a
    /// gate slower or faster than its profile says switches on that much late or early.
    /// </remarks>
    public double GateProcessingMs { get; init; } = 0.19;

    /// <summary>Half-width of the spread of <see cref="GateProcessingMs"/>, ms.</summary>
    public double GateProcessingJitterMs { get; init; } = 0.03;

    /// <summary>
    /// How late this computer wakes from a timed wait, ms: the lateness 98 % of its waits stay within (`machine latency` measures it). A switching the host
    /// times itself lands that much late, so it sets the fastest burn speed the edge tolerance holds (<see cref="Jobs.SpeedHold"/>).
    /// </summary>
    /// <remarks>The default describes a lab PC, as the twin's realistic host: waits up to 0.5 ms late, 1 % of them up to 5 ms.</remarks>
    public double HostLatenessMs { get; init; } = 0.5;

    /// <summary>
    /// The longest lateness of a timed wait this computer showed, ms (the tail beyond <see cref="HostLatenessMs"/>): a
    /// scheduled switch-on's lead time must cover it, or that switch-on goes plain and the tolerance rules it.
    /// </summary>
    public double HostLatenessTailMs { get; init; } = 5;
}

/// <summary>The machine: two Zaber axes, the laser gate, the spot and the default process settings.</summary>
public sealed record MachineProfile
{
    private static readonly JsonSerializerOptions JsonOptions = new()
    {
        WriteIndented = true,
        PropertyNamingPolicy = JsonNamingPolicy.CamelCase,
        ReadCommentHandling = JsonCommentHandling.Skip,
        AllowTrailingCommas = true,

        // A misspelt field ("watchdogMS") would otherwise leave the default in force without a word.
        UnmappedMemberHandling = JsonUnmappedMemberHandling.Disallow,
    };

    public string Name { get; init; } = "Two Zaber T-LA60A (default)";

    public AxisProfile X { get; init; } = new() { DeviceNumber = 1 };

    public AxisProfile Y { get; init; } = new() { DeviceNumber = 2 };

    /// <summary>The focus axis, a third Zaber device on the same chain; null (absent from the file) on a two-axis machine.</summary>
    [JsonIgnore(Condition = JsonIgnoreCondition.WhenWritingNull)]
    public ZAxisProfile? Z { get; init; }

    /// <summary>Baud rate of the Zaber chain (T-series speak only 9600).</summary>
    public int StageBaudRate { get; init; } = 9600;

    /// <summary>Focused laser spot diameter, µm.</summary>
    public double SpotDiameterUm { get; init; } = 20;

    /// <summary>Default speed while burning, mm/s.</summary>
    public double BurnSpeedMmPerS { get; init; } = 1;

    /// <summary>Default speed while travelling with the laser off, mm/s.</summary>
    public double TravelSpeedMmPerS { get; init; } = 4;

    /// <summary>Default acceleration, mm/s².</summary>
    public double AccelerationMmPerS2 { get; init; } = 50;

    /// <summary>Default Q-switch frequency while burning, Hz (seed 000 used 1 kHz).</summary>
    public double LaserFrequencyHz { get; init; } = 1000;

    /// <summary>Highest frequency `frame --visible-hz` may fire at while tracing the outline, Hz: low, to see the frame, not to burn it.</summary>
    public int MaxFrameFrequencyHz { get; init; } = 100;

    public LaserGateProfile Gate { get; init; } = new();

    /// <summary>
    /// How far a switching may land from its place at the burn speed, µm, when the computer is late to send it: within it
    /// the switch is counted and logged; beyond it the laser stays off for that run and the run stops as a timing doubt
    /// (which a session recovers from). The default keeps every edge within 3 µm on the twin's defaults.
    /// </summary>
    public double EdgeToleranceUm { get; init; } = 1.5;

    /// <summary>Serial latencies besides the wire time, measured by `laserengrave machine latency`.</summary>
    public LatencyProfile Latency { get; init; } = new();

    /// <summary>
    /// The bidirectional scan offsets, by burn speed (`laserengrave pattern scan-offset` shows what to enter): right-to-left
    /// rows are shifted by the offset at the burn speed; null (absent from the file) or empty means none.
    /// </summary>
    [JsonIgnore(Condition = JsonIgnoreCondition.WhenWritingNull)]
    public IReadOnlyList<ScanOffset>? ScanOffsets { get; init; }

    /// <summary>The stage's squareness and scale errors from `laserengrave calibrate solve`; null (absent from the file) means uncalibrated.</summary>
    [JsonIgnore(Condition = JsonIgnoreCondition.WhenWritingNull)]
    public AxisCalibration? Calibration { get; init; }

    /// <summary>The camera on the optical path (docs/camera.md); null (absent from the file) on a machine without one.</summary>
    [JsonIgnore(Condition = JsonIgnoreCondition.WhenWritingNull)]
    public CameraProfile? Camera { get; init; }

    /// <summary>The built-in profile: two Zaber T-LA60A, device 1 = X, device 2 = Y.</summary>
    public static MachineProfile Default { get; } = new();

    /// <summary>Reads and checks a profile; throws a <see cref="ProfileException"/> of one line naming the file and the field.</summary>
    public static MachineProfile Load(string path)
    {
        ArgumentException.ThrowIfNullOrEmpty(path);
        if (RegularFile.Problem(path) is { } problem)
        {
            throw new ProfileException($"{path}: {problem}");
        }

        string text;
        try
        {
            text = TextFile.Read(path);
        }
        catch (TextEncodingException ex)
        {
            throw new ProfileException($"{path}: {ex.Message}", ex);
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            throw new ProfileException($"{path}: cannot read the machine profile: {ex.Message}", ex);
        }

        MachineProfile? profile;
        try
        {
            profile = JsonSerializer.Deserialize<MachineProfile>(text, JsonOptions);
        }
        catch (JsonException ex)
        {
            throw new ProfileException($"{path}: {MachineProfileValidator.DescribeJsonError(ex, text)}", ex);
        }

        if (profile is null)
        {
            throw new ProfileException($"{path}: the machine profile is empty");
        }

        profile.Validate(path);
        return profile;
    }

    /// <summary>The scan offset at <paramref name="burnSpeedMmPerS"/>, µm (<see cref="ScanOffset.At"/>).</summary>
    public double ScanOffsetUmAt(double burnSpeedMmPerS) => ScanOffset.At(ScanOffsets, burnSpeedMmPerS);

    public string ToJson() => JsonSerializer.Serialize(this, JsonOptions);

    public void Save(string path) => File.WriteAllText(path, ToJson());

    /// <summary>Checks every value is usable; throws a <see cref="ProfileException"/> naming the first that is not.</summary>
    /// <remarks>The rules are <see cref="MachineProfileValidator"/>'s.</remarks>
    public void Validate(string source = "profile") => MachineProfileValidator.Validate(this, source);
}

/// <summary>A machine profile that cannot be read or holds an unusable value.</summary>
public sealed class ProfileException : Exception
{
    public ProfileException(string message)
        : base(message)
    {
    }

    public ProfileException(string message, Exception inner)
        : base(message, inner)
    {
    }
}
