using System.Text.Json;
using System.Text.Json.Serialization;

namespace LaserEngrave.App.Services;

/// <summary>One JSON file per run in a folder (the run log of branch `logging` replaces it once merged).</summary>
public sealed class JsonRunLogStore(string folder) : IRunLogStore
{
    internal static readonly JsonSerializerOptions Options = new(JsonSerializerDefaults.Web)
    {
        WriteIndented = true,
        Converters = { new JsonStringEnumConverter() },
    };

    public string Folder => folder;

    public void Save(RunRecord record)
    {
        ArgumentNullException.ThrowIfNull(record);
        Directory.CreateDirectory(folder);
        File.WriteAllText(Path.Combine(folder, $"run-{record.Id}.json"), JsonSerializer.Serialize(record, Options));
    }

    public IReadOnlyList<RunRecord> History()
    {
        if (!Directory.Exists(folder))
        {
            return [];
        }

        var records = new List<RunRecord>();
        foreach (var file in Directory.EnumerateFiles(folder, "run-*.json"))
        {
            try
            {
                if (JsonSerializer.Deserialize<RunRecord>(File.ReadAllText(file), Options) is { } record)
                {
                    records.Add(record);
                }
            }
            catch (Exception ex) when (ex is IOException or JsonException)
            {
                // A damaged log is left out of the list rather than hiding every other run.
            }
        }

        return [.. records.OrderByDescending(r => r.StartedUtc)];
    }
}
