using System.Text.Json;
using System.Text.Json.Nodes;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Logging;

/// <summary>
/// Brings a run record of an older schema version up to <see cref="RunRecord.CurrentSchemaVersion"/>, one version at a
/// time, so that every log this program ever wrote can be repeated and resumed (docs/run-log.md, "Older logs").
/// </summary>
/// <remarks>
/// Each step takes the JSON of version N and gives that of N + 1; the reader then reads it as strictly as a new log. Tests
/// keep genuine logs of every version (tests/LaserEngrave.Core.Tests/Logging/Fixtures) and repeat and resume each.
/// </remarks>
public static class RunLogMigration
{
    // Step i turns version i + 1 into version i + 2.
    private static readonly Func<JsonObject, JsonObject>[] Steps = [FromVersion1, FromVersion2];

    /// <summary>The record's JSON at <see cref="RunRecord.CurrentSchemaVersion"/>; <paramref name="version"/> is the one it was written with.</summary>
    public static JsonObject ToCurrent(JsonObject record, int version)
    {
        ArgumentNullException.ThrowIfNull(record);
        ArgumentOutOfRangeException.ThrowIfLessThan(version, 1);
        ArgumentOutOfRangeException.ThrowIfGreaterThan(version, RunRecord.CurrentSchemaVersion);
        for (var v = version; v < RunRecord.CurrentSchemaVersion; v++)
        {
            record = Steps[v - 1](record);
            record["schemaVersion"] = v + 1;
        }

        return record;
    }

    /// <summary>
    /// Version 1 grew over its life (2026-11-23 to 2026-11-28): the profile gained its latency section, the gate's
    /// highest frequency, the edge tolerance; the process its dot mode; the record its passes. A log written before a
    /// member existed does not have it, and the strict reader would read it as 0 or null ("profile.latency must not be
    /// null", "gate.maxFrequencyHz ... got 0", "pulsesPerDot 0"). Each member an older log lacks takes the value
    /// `--profile` gives a profile file that leaves it out: today's default, which is also what that program did
    /// without it (one pass, raster, no latency known). Version 2 logs are written whole, so the reader can stay strict.
    /// </summary>
    private static JsonObject FromVersion1(JsonObject record)
    {
        FillMissing(record, "profile", Node(MachineProfile.Default));
        if (record["profile"] is JsonObject { } profile && profile["z"] is JsonObject)
        {
            FillMissing(profile, "z", Node(new ZAxisProfile()));
        }

        FillMissing(record, "process", Node(ProcessSettings.Default));
        FillMissing(record, "mask", Node(new MaskOptions()));
        FillMissing(record, "plan", Node(new PlanOptions()));
        record["passes"] ??= 1;
        return record;
    }

    /// <summary>
    /// Version 2 (2026-11-29, morning) was written before the gate gained its kind (`kind`, `neverReplies`: a gate that
    /// only sets a frequency), the scheduled burst (`burstAfterCommand`, `burstAfterReply`) and the capabilities question
    /// (`capabilitiesCommand`, `capabilitiesReply`), and the profile its optional `camera`. Each member it lacks in the
    /// profile takes the value `--profile` gives when it is left out: the counted-burst gate every version 2 log ran
    /// with, its default command strings (which that program never sent), and no camera.
    /// </summary>
    private static JsonObject FromVersion2(JsonObject record)
    {
        FillMissing(record, "profile", Node(MachineProfile.Default));
        return record;
    }

    private static JsonObject Node<T>(T value) => (JsonObject)RunRecordJson.ToNode(value);

    // Adds to record[name] every member (at any depth) of defaults it lacks; a member given, even null, is kept as given.
    private static void FillMissing(JsonObject record, string name, JsonObject defaults)
    {
        if (record[name] is JsonObject given)
        {
            Merge(given, defaults);
        }
    }

    private static void Merge(JsonObject given, JsonObject defaults)
    {
        foreach (var (key, value) in defaults)
        {
            if (!given.TryGetPropertyValue(key, out var existing))
            {
                given[key] = value?.DeepClone();
            }
            else if (existing is JsonObject inner && value is JsonObject innerDefaults)
            {
                Merge(inner, innerDefaults);
            }
        }
    }

    /// <summary>The schema version a record's JSON names, or null when it names none (the strict reader then says what is wrong).</summary>
    internal static int? VersionOf(JsonObject record) =>
        record["schemaVersion"] is JsonValue value && value.GetValueKind() == JsonValueKind.Number && value.TryGetValue(out int version) ? version : null;
}
