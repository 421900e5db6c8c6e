using System.Text.Json;
using System.Text.Json.Serialization;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Jobs;

/// <summary>A named set of process values to burn a material with, kept in the preset library: a named subset of <see cref="JobSettings"/>.</summary>
public sealed record ProcessPreset
{
    public required string Name { get; init; }

    public double LaserFrequencyHz { get; init; } = 1000;

    public double BurnSpeedMmPerS { get; init; } = 1;

    public double TravelSpeedMmPerS { get; init; } = 4;

    public int Passes { get; init; } = 1;

    public double PitchUm { get; init; } = 50;

    public double OverscanMm { get; init; }

    public string? Notes { get; init; }

    /// <summary>The source papers' settings, shipped as examples.</summary>
    public static IReadOnlyList<ProcessPreset> Examples { get; } =
    [
        new()
        {
            Name = "Si wafer, 1 kHz Q-switch (paper 000)",
            LaserFrequencyHz = 1000,
            BurnSpeedMmPerS = 1,
            TravelSpeedMmPerS = 4,
            PitchUm = 50,
            Notes = "Nd:YAG, acousto-optic Q-switch at 1 kHz, f = 25 mm lens, 350 µm silicon wafers; QR codes and drawings (the source paper's own process).",
        },
        new()
        {
            Name = "Si(100), 20 kHz 150 µJ (paper 001)",
            LaserFrequencyHz = 20000,
            BurnSpeedMmPerS = 2,
            TravelSpeedMmPerS = 4,
            PitchUm = 20,
            Notes = "355 nm ns laser, 20 kHz, 150 µJ per pulse, 2 mm/s; hexagons cut in Si(100), spot < 20 µm (from the hexagon-cutting paper). Set the pulse energy on the laser itself.",
        },
    ];

    /// <summary>The fields of <see cref="JobSettings"/> a preset holds.</summary>
    public static IReadOnlyList<string> Fields { get; } = [JobField.Frequency, JobField.BurnSpeed, JobField.TravelSpeed, JobField.Passes, JobField.Pitch, JobField.Overscan];

    /// <summary><paramref name="settings"/> with the preset's values; its pitch too when <paramref name="withPitch"/> (which sizes the job by pitch).</summary>
    public JobSettings ApplyTo(JobSettings settings, bool withPitch = true)
    {
        ArgumentNullException.ThrowIfNull(settings);
        var applied = settings with
        {
            LaserFrequencyHz = LaserFrequencyHz,
            BurnSpeedMmPerS = BurnSpeedMmPerS,
            TravelSpeedMmPerS = TravelSpeedMmPerS,
            Passes = Passes,
            OverscanMm = OverscanMm,
        };
        return withPitch ? applied with { SizeMode = SizeMode.Pitch, PitchUm = PitchUm } : applied;
    }

    /// <summary>The preset's values the job rules refuse on a machine of <paramref name="limits"/> (<see cref="JobRules.Check(JobSettings, MachineLimits)"/>).</summary>
    public IReadOnlyList<FieldProblem> Check(MachineLimits limits) =>
        [.. JobRules.Check(ApplyTo(new JobSettings()), limits).Where(p => Fields.Contains(p.Field))];

    private static readonly JsonSerializerOptions Json = new(JsonSerializerDefaults.Web) { WriteIndented = true, DefaultIgnoreCondition = JsonIgnoreCondition.WhenWritingNull };

    public static string ToJson(IEnumerable<ProcessPreset> presets) => JsonSerializer.Serialize(presets.ToList(), Json);

    /// <summary>Reads a list of presets; throws <see cref="JsonException"/> or <see cref="ArgumentException"/> naming what is wrong.</summary>
    /// <remarks>Its values are the machine's to judge: <see cref="Check"/> with the machine's limits before a preset is used.</remarks>
    public static IReadOnlyList<ProcessPreset> FromJson(string json)
    {
        var presets = JsonSerializer.Deserialize<List<ProcessPreset>>(json, Json) ?? throw new JsonException("not a list of presets");
        foreach (var preset in presets)
        {
            if (string.IsNullOrWhiteSpace(preset.Name))
            {
                throw new ArgumentException("a preset without a name");
            }
        }

        return presets;
    }
}
