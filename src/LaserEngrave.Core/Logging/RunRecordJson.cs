using System.Text.Encodings.Web;
using System.Text.Json;
using System.Text.Json.Nodes;

namespace LaserEngrave.Core.Logging;

/// <summary>Turns a <see cref="RunRecord"/> into its JSON text and back (the format of docs/run-log.md).</summary>
public static class RunRecordJson
{
    // Relaxed escaping keeps '+', 'µ' and accented notes readable in the file; the text is never embedded in HTML.
    private static readonly RunLogJsonContext Context = new(new JsonSerializerOptions(RunLogJsonContext.Default.Options)
    {
        Encoder = JavaScriptEncoder.UnsafeRelaxedJsonEscaping,
        TypeInfoResolver = null,
    });

    /// <summary>Builds the serializer's metadata now, so that the first <see cref="Serialize"/> does not wait for it.</summary>
    /// <remarks>
    /// About a tenth of a second of compiling in a fresh process: a front end calls it on another thread while a run goes
    /// on (the simulation runs on one thread), so that writing the log at the end does not add that time.
    /// </remarks>
    public static void Prepare() => _ = Context.Options.GetTypeInfo(typeof(RunRecord));

    public static string Serialize(RunRecord record)
    {
        ArgumentNullException.ThrowIfNull(record);
        return JsonSerializer.Serialize(record, Context.RunRecord);
    }

    /// <summary>Parses a record; throws <see cref="RunLogException"/> with one line naming <paramref name="source"/> and the problem.</summary>
    public static RunRecord Deserialize(string json, string source)
    {
        ArgumentNullException.ThrowIfNull(json);
        (json, var readFrom) = Migrated(json);
        RunRecord? record;
        try
        {
            record = JsonSerializer.Deserialize(json, Context.RunRecord);
        }
        catch (JsonException ex)
        {
            throw new RunLogException($"{source}: {IO.JsonProblem.Describe(ex, "run log")}", ex);
        }

        if (record is null)
        {
            throw new RunLogException($"{source}: not a run log: it holds null");
        }

        if (record.SchemaVersion is < 1 or > RunRecord.CurrentSchemaVersion)
        {
            throw new RunLogException(
                $"{source}: run log schema version {record.SchemaVersion} is not one this LaserEngrave reads (1..{RunRecord.CurrentSchemaVersion}); use a newer LaserEngrave");
        }

        return readFrom is { } version ? record with { ReadFromSchemaVersion = version } : record;
    }

    /// <summary>A value as the run log writes it, as a JSON node (for <see cref="RunLogMigration"/>'s defaults).</summary>
    internal static JsonNode ToNode<T>(T value) =>
        JsonSerializer.SerializeToNode(value, Context.Options.GetTypeInfo(typeof(T))) ?? throw new InvalidOperationException($"{typeof(T).Name} has no JSON");

    // An older schema version's JSON brought up to this one; anything else (this version, a newer one, no record at all)
    // as it is, for the strict reader to read or name what is wrong with it.
    private static (string Json, int? ReadFrom) Migrated(string json)
    {
        JsonNode? node;
        try
        {
            node = JsonNode.Parse(json, documentOptions: new JsonDocumentOptions { AllowTrailingCommas = true, CommentHandling = JsonCommentHandling.Skip });
        }
        catch (JsonException)
        {
            return (json, null);
        }

        return node is JsonObject record && RunLogMigration.VersionOf(record) is { } version && version >= 1 && version < RunRecord.CurrentSchemaVersion
            ? (RunLogMigration.ToCurrent(record, version).ToJsonString(Context.Options), version)
            : (json, null);
    }
}
