using System.Text.Json;
using System.Text.Json.Serialization;

namespace LaserEngrave.App.Services;

/// <summary>A named set of process values to burn a material with, kept in the preset library.</summary>
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
            Notes = "Nd:YAG, acousto-optic Q-switch at 1 kHz, f = 25 mm lens, 350 µm silicon wafers; QR codes and drawings (seed 000).",
        },
        new()
        {
            Name = "Si(100), 20 kHz 150 µJ (paper 001)",
            LaserFrequencyHz = 20000,
            BurnSpeedMmPerS = 2,
            TravelSpeedMmPerS = 4,
            PitchUm = 20,
            Notes = "355 nm ns laser, 20 kHz, 150 µJ per pulse, 2 mm/s; hexagons cut in Si(100), spot < 20 µm (seed 001). Set the pulse energy on the laser itself.",
        },
    ];

    private static readonly JsonSerializerOptions Json = new(JsonSerializerDefaults.Web) { WriteIndented = true, DefaultIgnoreCondition = JsonIgnoreCondition.WhenWritingNull };

    public static string ToJson(IEnumerable<ProcessPreset> presets) => JsonSerializer.Serialize(presets.ToList(), Json);

    /// <summary>Reads a list of presets; throws <see cref="JsonException"/> or <see cref="ArgumentException"/> naming what is wrong.</summary>
    public static IReadOnlyList<ProcessPreset> FromJson(string json)
    {
        var presets = JsonSerializer.Deserialize<List<ProcessPreset>>(json, Json) ?? throw new JsonException("not a list of presets");
        foreach (var preset in presets)
        {
            if (string.IsNullOrWhiteSpace(preset.Name))
            {
                throw new ArgumentException("a preset without a name");
            }

            if (!(preset.LaserFrequencyHz >= 1) || !(preset.BurnSpeedMmPerS > 0) || !(preset.TravelSpeedMmPerS > 0) || preset.Passes is < 1 or > 100 || !(preset.PitchUm > 0) || !(preset.OverscanMm >= 0))
            {
                throw new ArgumentException($"preset \"{preset.Name}\": a value is out of range (frequency ≥ 1 Hz, speeds and pitch above 0, passes 1 to 100, overscan ≥ 0)");
            }
        }

        return presets;
    }
}
