using System.Text.Json;
using System.Text.Json.Serialization;
using LaserEngrave.Simulator.Serial;
using LaserEngrave.Simulator.Timing;

namespace LaserEngrave.Simulator;

/// <summary>Reads a simulator options file (<c>--sim-options FILE.json</c>, docs/simulator.md): every field optional, unknown fields refused.</summary>
public static class SimulatorOptionsFile
{
    private static readonly JsonSerializerOptions Json = new()
    {
        PropertyNamingPolicy = JsonNamingPolicy.CamelCase,
        ReadCommentHandling = JsonCommentHandling.Skip,
        AllowTrailingCommas = true,
        UnmappedMemberHandling = JsonUnmappedMemberHandling.Disallow,
    };

    /// <summary>The options of <paramref name="path"/> applied over <paramref name="baseOptions"/>.</summary>
    /// <exception cref="InvalidDataException">The file cannot be read, or a field is wrong; one line naming the file and the field.</exception>
    public static SimulatorOptions Load(string path, SimulatorOptions baseOptions)
    {
        ArgumentNullException.ThrowIfNull(path);
        ArgumentNullException.ThrowIfNull(baseOptions);
        Fields? fields;
        try
        {
            fields = JsonSerializer.Deserialize<Fields>(File.ReadAllText(path), Json);
        }
        catch (JsonException ex)
        {
            throw new InvalidDataException($"{path}: {Describe(ex)}", ex);
        }
        catch (IOException ex)
        {
            throw new InvalidDataException($"{path}: cannot read the simulator options: {ex.Message}", ex);
        }
        catch (UnauthorizedAccessException ex)
        {
            throw new InvalidDataException($"{path}: cannot read the simulator options: {ex.Message}", ex);
        }

        if (fields is null)
        {
            throw new InvalidDataException($"{path}: the simulator options must be a JSON object");
        }

        var options = baseOptions with
        {
            Seed = fields.Seed ?? baseOptions.Seed,
            GateScheduledBursts = fields.GateScheduledBursts ?? baseOptions.GateScheduledBursts,
            AdapterLatency = Checked(path, "adapterLatency", fields.AdapterLatency) ?? baseOptions.AdapterLatency,
            GateProcessing = Checked(path, "gateProcessing", fields.GateProcessing) ?? baseOptions.GateProcessing,
            TargetSpeedData = InRange(path, "targetSpeedData", fields.TargetSpeedData, 1, 32767) ?? baseOptions.TargetSpeedData,
            HomeSpeedData = InRange(path, "homeSpeedData", fields.HomeSpeedData, 1, 32767) ?? baseOptions.HomeSpeedData,
            AccelerationData = InRange(path, "accelerationData", fields.AccelerationData, 0, 32767) ?? baseOptions.AccelerationData,
            FaultSpec = fields.Faults ?? baseOptions.FaultSpec,
            HostLateness = CheckedLateness(path, fields.HostLateness) ?? baseOptions.HostLateness,
            ReplyPieces = CheckedPieces(path, fields.ReplyPieces) ?? baseOptions.ReplyPieces,
            FirmwareVersion = InRange(path, "firmwareVersion", fields.FirmwareVersion, 500, 599) ?? baseOptions.FirmwareVersion,
            DeviceId = InRange(path, "deviceId", fields.DeviceId, 1, int.MaxValue) ?? baseOptions.DeviceId,
            StartMm = fields.StartMm is { } startMm
                ? double.IsFinite(startMm) && startMm >= 0 && startMm <= 1000 ? startMm : throw new InvalidDataException($"{path}: startMm must be 0..1000 mm (got {startMm.ToString(System.Globalization.CultureInfo.InvariantCulture)})")
                : baseOptions.StartMm,
            Paced = fields.Paced ?? baseOptions.Paced,
        };
        if (fields.TrueFocusOffsetUm is { } focusOffset)
        {
            options = options with
            {
                TrueFocusOffsetUm = double.IsFinite(focusOffset) && Math.Abs(focusOffset) <= 100_000 ? focusOffset : throw new InvalidDataException($"{path}: trueFocusOffsetUm must be -100000..100000 µm (got {focusOffset.ToString(System.Globalization.CultureInfo.InvariantCulture)})"),
            };
        }

        if (fields.RayleighLengthUm is { } rayleigh)
        {
            options = options with
            {
                RayleighLengthUm = double.IsFinite(rayleigh) && rayleigh > 0 && rayleigh <= 100_000 ? rayleigh : throw new InvalidDataException($"{path}: rayleighLengthUm must be above 0 and at most 100000 µm (got {rayleigh.ToString(System.Globalization.CultureInfo.InvariantCulture)})"),
            };
        }

        if (fields.JitterScale is { } scale)
        {
            if (!double.IsFinite(scale) || scale < 0 || scale > 100)
            {
                throw new InvalidDataException($"{path}: jitterScale {scale} must be 0 to 100");
            }

            options = options with
            {
                AdapterLatency = options.AdapterLatency.WithSpreadScaled(scale),
                GateProcessing = options.GateProcessing?.WithSpreadScaled(scale),
            };
        }

        return options;
    }

    // System.Text.Json names its own types in its messages; the user needs the field and what is wrong with it.
    private static string Describe(JsonException ex)
    {
        var field = ex.Path is { Length: > 2 } p ? p[2..] : null;
        var line = ex.LineNumber is { } n ? $" (line {n + 1})" : string.Empty;
        if (ex.Message.Contains("could not be mapped", StringComparison.Ordinal))
        {
            var name = ex.Message.Split('\'') is { Length: > 2 } parts ? parts[1] : field;
            return $"unknown field '{name}'{line}; the fields are {string.Join(", ", KnownFields)}";
        }

        return field is null ? $"not a JSON object of simulator options{line}" : $"field '{field}' has a value of the wrong kind{line}";
    }

    private static readonly string[] KnownFields =
        ["seed", "firmwareVersion", "deviceId", "hostLateness", "replyPieces", "adapterLatency", "gateProcessing", "jitterScale", "targetSpeedData", "homeSpeedData", "accelerationData", "startMm", "paced", "faults", "trueFocusOffsetUm", "rayleighLengthUm"];

    private static Jitter? Checked(string path, string name, Jitter? jitter)
    {
        if (jitter is { } j && (!double.IsFinite(j.MeanMs) || !double.IsFinite(j.SpreadMs) || j.MeanMs < 0 || j.SpreadMs < 0 || j.MeanMs > 1000 || j.SpreadMs > 1000))
        {
            throw new InvalidDataException($"{path}: {name} must have meanMs and spreadMs from 0 to 1000 ms");
        }

        return jitter;
    }

    private static HostLateness? CheckedLateness(string path, HostLateness? lateness) =>
        lateness is { } l && (!Within(l.TypicalMs, 1000) || !Within(l.TailMs, 1000) || !Within(l.TailProbability, 1))
            ? throw new InvalidDataException($"{path}: hostLateness must have typicalMs and tailMs from 0 to 1000 ms and tailProbability from 0 to 1")
            : lateness is { } s && (!Within(s.StallMs, 1000) || !Within(s.LateReadMs, 1000) || !Within(s.StallProbability, 1) || !Within(s.LateReadProbability, 1))
            ? throw new InvalidDataException($"{path}: hostLateness must have stallMs and lateReadMs from 0 to 1000 ms and stallProbability and lateReadProbability from 0 to 1")
            : lateness;

    private static ReplyPieces? CheckedPieces(string path, ReplyPieces? pieces) =>
        pieces is { } p && (!Within(p.Probability, 1) || !Within(p.GapMs, 100))
            ? throw new InvalidDataException($"{path}: replyPieces must have probability from 0 to 1 and gapMs from 0 to 100 ms")
            : pieces;

    private static bool Within(double value, double max) => double.IsFinite(value) && value >= 0 && value <= max;

    private static int? InRange(string path, string name, int? value, int min, int max) =>
        value is { } v && (v < min || v > max)
            ? throw new InvalidDataException($"{path}: {name} {v} must be {min} to {max}")
            : value;

    private sealed record Fields
    {
        public int? Seed { get; init; }

        public bool? GateScheduledBursts { get; init; }

        public int? FirmwareVersion { get; init; }

        public HostLateness? HostLateness { get; init; }

        public ReplyPieces? ReplyPieces { get; init; }

        public int? DeviceId { get; init; }

        public Jitter? AdapterLatency { get; init; }

        public Jitter? GateProcessing { get; init; }

        public double? JitterScale { get; init; }

        public int? TargetSpeedData { get; init; }

        public int? HomeSpeedData { get; init; }

        public int? AccelerationData { get; init; }

        public double? StartMm { get; init; }

        public bool? Paced { get; init; }

        public string? Faults { get; init; }

        public double? TrueFocusOffsetUm { get; init; }

        public double? RayleighLengthUm { get; init; }
    }
}
