using System.Text.Json;
using System.Text.Json.Serialization;
using LaserEngrave.Core.Calibration;
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

/// <summary>How the laser gate is spoken to; every string is overridable for a PIC that speaks differently.</summary>
public sealed record LaserGateProfile
{
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

    /// <summary>Every successful reply starts with this.</summary>
    public string AckPrefix { get; init; } = "OK";

    /// <summary>Every refusal starts with this.</summary>
    public string ErrorPrefix { get; init; } = "ERR";

    public string LineTerminator { get; init; } = "\n";

    /// <summary>How long to wait for an acknowledgement before the gate counts as silent.</summary>
    public int TimeoutMs { get; init; } = 500;

    /// <summary>Watchdog time programmed into the gate: it switches the laser off after this long without a command (50..60000).</summary>
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
    public double GateProcessingMs { get; init; } = 0.5;

    /// <summary>Half-width of the spread of <see cref="GateProcessingMs"/>, ms.</summary>
    public double GateProcessingJitterMs { get; init; } = 0.2;
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
            text = File.ReadAllText(path);
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
            throw new ProfileException($"{path}: {MachineProfileValidator.DescribeJsonError(ex)}", ex);
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
