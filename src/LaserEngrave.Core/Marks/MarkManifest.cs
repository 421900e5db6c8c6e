using System.Text.Json;
using System.Text.Json.Serialization;

namespace LaserEngrave.Core.Marks;

/// <summary>
/// The marks' record beside their job file (marks.json): which counter a completed run advances, from which number and
/// by how many, and every copy's text and place. A run of the job reads it to advance the counter when it completes.
/// </summary>
/// <param name="Counter">The counter file.</param>
/// <param name="FirstNumber">The first copy's number.</param>
/// <param name="Count">How many numbers the job burns.</param>
/// <param name="Marks">Every copy's code and text as placed.</param>
public sealed record MarkManifest(string Counter, int FirstNumber, int Count, IReadOnlyList<PlacedMark> Marks)
{
    private static readonly JsonSerializerOptions Options = new()
    {
        PropertyNamingPolicy = JsonNamingPolicy.CamelCase,
        WriteIndented = true,
        DefaultIgnoreCondition = JsonIgnoreCondition.WhenWritingNull,
    };

    public static void Write(string path, MarkManifest manifest) => File.WriteAllText(path, JsonSerializer.Serialize(manifest, Options) + "\n");

    /// <summary>The record beside <paramref name="jobFile"/>, or null when that job is not one of marks.</summary>
    /// <exception cref="MarkException">The record is there but unreadable.</exception>
    public static MarkManifest? Beside(string jobFile)
    {
        var path = Path.Combine(Path.GetDirectoryName(Path.GetFullPath(jobFile)) ?? ".", MarkLayout.ManifestFileName);
        if (!File.Exists(path))
        {
            return null;
        }

        try
        {
            return JsonSerializer.Deserialize<MarkManifest>(File.ReadAllText(path), Options) ?? throw new MarkException($"{path}: empty");
        }
        catch (JsonException ex)
        {
            throw new MarkException($"{path}: not a marks record ({ex.Message})", ex);
        }
    }

    /// <summary>After a run of the job beside it: advances the counter when the run completed, and only then.</summary>
    /// <returns>The counter's next number after a completed run; null otherwise.</returns>
    public static int? AfterRun(string jobFile, Jobs.RunOutcome outcome) =>
        outcome == Jobs.RunOutcome.Completed && Beside(jobFile) is { } manifest
            ? new MarkCounter(manifest.Counter).Complete(manifest.FirstNumber, manifest.Count)
            : null;
}
