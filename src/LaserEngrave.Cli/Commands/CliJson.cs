using System.Text.Encodings.Web;
using System.Text.Json;
using System.Text.Json.Serialization;

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
    };

    /// <summary>Builds the metadata for <paramref name="type"/> now (on another thread while a run goes on), so that writing it later does not wait for it.</summary>
    public static void Prepare(Type type)
    {
        // As the first Serialize would: the default (reflection) resolver, and the options frozen.
        Options.MakeReadOnly(populateMissingResolver: true);
        _ = Options.GetTypeInfo(type);
    }

    public static void Write(TextWriter output, object value) => output.WriteLine(JsonSerializer.Serialize(value, value.GetType(), Options));
}
