using System.Text.Json;
using System.Text.Json.Serialization;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Logging;

/// <summary>The source-generated serializer of run records: camelCase, indented, enums as camelCase strings, strict on read.</summary>
/// <remarks>
/// Strict reading (required members and constructor parameters, nullable annotations) turns a hand-edited record with
/// a missing or null value into a one-line error instead of a record that fails later.
/// </remarks>
[JsonSourceGenerationOptions(
    JsonSerializerDefaults.Web,
    WriteIndented = true,
    AllowTrailingCommas = true,
    ReadCommentHandling = JsonCommentHandling.Skip,
    NumberHandling = JsonNumberHandling.AllowNamedFloatingPointLiterals,
    RespectNullableAnnotations = true,
    RespectRequiredConstructorParameters = true,
    Converters =
    [
        typeof(CamelCaseEnumConverter<RunOutcome>),
        typeof(CamelCaseEnumConverter<RunSizeKind>),
        typeof(CamelCaseEnumConverter<DitherMethod>),
        typeof(CamelCaseEnumConverter<PlanStrategy>),
        typeof(CamelCaseEnumConverter<PlanMode>),
        typeof(CamelCaseEnumConverter<Vectors.VectorFillMode>),
        typeof(CamelCaseEnumConverter<LayerMode>),
        typeof(CamelCaseEnumConverter<LaserOffPath>),
    ])]
[JsonSerializable(typeof(RunRecord))]
[JsonSerializable(typeof(SweepRecord))]
internal sealed partial class RunLogJsonContext : JsonSerializerContext;

/// <summary>Writes an enum as its camelCase name, e.g. "floydSteinberg", and reads it back in any case.</summary>
internal sealed class CamelCaseEnumConverter<TEnum>() : JsonStringEnumConverter<TEnum>(JsonNamingPolicy.CamelCase, allowIntegerValues: false)
    where TEnum : struct, Enum;
