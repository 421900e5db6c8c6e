using System.Text.Encodings.Web;
using System.Text.Json;
using System.Text.Json.Serialization;
using System.Text.Json.Serialization.Metadata;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Cli.Commands;

/// <summary>How every `--json` output is written: one camelCase object, enums as strings.</summary>
internal static class CliJson
{
    public static readonly JsonSerializerOptions Options = new()
    {
        PropertyNamingPolicy = JsonNamingPolicy.CamelCase,
        WriteIndented = true,
        Encoder = JavaScriptEncoder.UnsafeRelaxedJsonEscaping,
        Converters = { new JsonStringEnumConverter(JsonNamingPolicy.CamelCase) },
        NumberHandling = JsonNumberHandling.AllowNamedFloatingPointLiterals,

        // The outputs' metadata compiled with the program (a published one starts without building it by reflection);
        // reflection only for a type not listed in CliJsonContext, so that such an output is still written, as before.
        TypeInfoResolver = JsonTypeInfoResolver.Combine(CliJsonContext.Default, new DefaultJsonTypeInfoResolver()),
    };

    /// <summary>Builds the metadata for <paramref name="type"/> now (on another thread while a run goes on), so that writing it later does not wait for it.</summary>
    public static void Prepare(Type type)
    {
        // As the first Serialize would: the options frozen, the type's metadata made.
        Options.MakeReadOnly();
        _ = Options.GetTypeInfo(type);
    }

    public static void Write(TextWriter output, object value) => output.WriteLine(JsonSerializer.Serialize(value, value.GetType(), Options));
}

/// <summary>
/// The source-generated metadata of every object a command writes with `--json` (<see cref="CliJson.Write"/>). The
/// options are <see cref="CliJson.Options"/>'s: the same names, order and text as the reflection-based serializer wrote.
/// </summary>
[JsonSerializable(typeof(AlignSummary))]
[JsonSerializable(typeof(CalibrationShowSummary))]
[JsonSerializable(typeof(CalibrationSolveSummary))]
[JsonSerializable(typeof(EngraveSummary))]
[JsonSerializable(typeof(ImageInfo))]
[JsonSerializable(typeof(JobSummary))]
[JsonSerializable(typeof(LatencySummary))]
[JsonSerializable(typeof(LayersSummary))]
[JsonSerializable(typeof(MachineCheckSummary))]
[JsonSerializable(typeof(MarkCommand.MarkSummary))]
[JsonSerializable(typeof(ProcessSummary))]
[JsonSerializable(typeof(SweepPlanSummary))]
[JsonSerializable(typeof(SweepRunSummary))]
[JsonSerializable(typeof(VectorSummary))]
internal sealed partial class CliJsonContext : JsonSerializerContext;
