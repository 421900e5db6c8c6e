using System.Globalization;
using System.Text.Json;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Marks;

/// <summary>
/// A mark from a JSON file: <c>{"text": "S-{n:000}", "code": "datamatrix", "sizeMm": 2, "copies": 10, ...}</c>, the
/// fields of <see cref="MarkSpec"/> (docs/marking.md). Unknown or bad values are refused with one line naming the file and the field.
/// </summary>
public static class MarkFile
{
    private static readonly string[] Fields =
        ["text", "code", "moduleUm", "sizeMm", "quietModules", "errorCorrection", "label", "textHeightMm", "align", "lineSpacing", "font", "gapMm", "originMm", "copies", "columns", "pitchMm", "speedMmPerS", "frequencyHz", "passes"];

    public static MarkSpec Load(string path)
    {
        ArgumentException.ThrowIfNullOrWhiteSpace(path);
        if (!File.Exists(path) && !Directory.Exists(path))
        {
            throw new MarkException($"{path}: no such file");
        }

        if (IO.RegularFile.Problem(path) is { } problem)
        {
            throw new MarkException($"{path}: {problem}");
        }

        if (new FileInfo(path).Length > 1_000_000)
        {
            throw new MarkException($"{path}: larger than 1 MB, which no marks file is");
        }

        try
        {
            using var document = JsonDocument.Parse(IO.TextFile.Read(path), new JsonDocumentOptions { AllowTrailingCommas = true, CommentHandling = JsonCommentHandling.Skip });
            return Read(document.RootElement, path);
        }
        catch (IO.TextEncodingException ex)
        {
            throw new MarkException($"{path}: {ex.Message}", ex);
        }
        catch (JsonException ex)
        {
            throw new MarkException($"{path}: {IO.JsonProblem.Describe(ex, "marks file")}", ex);
        }
    }

    /// <summary>Reads one mark from <paramref name="element"/>; <paramref name="where"/> starts every message.</summary>
    public static MarkSpec Read(JsonElement element, string where)
    {
        if (element.ValueKind != JsonValueKind.Object)
        {
            throw new MarkException($"{where}: a mark is a JSON object");
        }

        foreach (var property in element.EnumerateObject())
        {
            if (!Fields.Contains(property.Name, StringComparer.Ordinal))
            {
                throw new MarkException($"{where}: unknown field \"{property.Name}\" (fields: {string.Join(", ", Fields)})");
            }
        }

        var code = String(element, "code", where) is { } c
            ? ParseCode(c) ?? (c.Trim().Equals("none", StringComparison.OrdinalIgnoreCase) ? null : throw new MarkException($"{where}: code \"{c}\" is not qr, datamatrix or none"))
            : null;
        var ecc = String(element, "errorCorrection", where) is { } e
            ? e.Trim().Length == 1 ? e.Trim()[0] : throw new MarkException($"{where}: errorCorrection \"{e}\" is not L, M, Q or H")
            : (char?)null;
        var align = String(element, "align", where) is { } a
            ? ParseAlign(a) ?? throw new MarkException($"{where}: align \"{a}\" is not left, center or right")
            : TextAlign.Center;
        var origin = Pair(element, "originMm", where) is { } o ? new OriginMm(o.X, o.Y) : new OriginMm(10, 10);
        var pitch = Pair(element, "pitchMm", where);
        return new MarkSpec
        {
            Text = String(element, "text", where) ?? throw new MarkException($"{where}: \"text\" is missing"),
            Code = code,
            ModuleUm = Number(element, "moduleUm", where),
            SizeMm = Number(element, "sizeMm", where),
            QuietModules = Whole(element, "quietModules", where),
            ErrorCorrection = ecc,
            Label = Bool(element, "label", where) ?? true,
            TextHeightMm = Number(element, "textHeightMm", where) ?? 0.4,
            Align = align,
            LineSpacing = Number(element, "lineSpacing", where) ?? 1.6,
            Font = String(element, "font", where),
            GapMm = Number(element, "gapMm", where) ?? 0.1,
            Origin = origin,
            Copies = Whole(element, "copies", where) ?? 1,
            Columns = Whole(element, "columns", where),
            PitchXMm = pitch?.X,
            PitchYMm = pitch?.Y,
            SpeedMmPerS = Number(element, "speedMmPerS", where),
            FrequencyHz = Number(element, "frequencyHz", where),
            Passes = Whole(element, "passes", where) ?? 1,
        };
    }

    /// <summary>qr, datamatrix (or data-matrix, dm); null for anything else.</summary>
    public static CodeKind? ParseCode(string text) => text.Trim().ToLowerInvariant() switch
    {
        "qr" => CodeKind.Qr,
        "datamatrix" or "data-matrix" or "dm" => CodeKind.DataMatrix,
        _ => null,
    };

    /// <summary>left, center (centre) or right; null for anything else.</summary>
    public static TextAlign? ParseAlign(string text) => text.Trim().ToLowerInvariant() switch
    {
        "left" => TextAlign.Left,
        "center" or "centre" => TextAlign.Center,
        "right" => TextAlign.Right,
        _ => null,
    };

    private static string? String(JsonElement element, string name, string where) =>
        !element.TryGetProperty(name, out var value) || value.ValueKind == JsonValueKind.Null ? null
        : value.ValueKind == JsonValueKind.String ? value.GetString()
        : throw new MarkException($"{where}: \"{name}\" must be a string");

    private static bool? Bool(JsonElement element, string name, string where) =>
        !element.TryGetProperty(name, out var value) || value.ValueKind == JsonValueKind.Null ? null
        : value.ValueKind is JsonValueKind.True or JsonValueKind.False ? value.GetBoolean()
        : throw new MarkException($"{where}: \"{name}\" must be true or false");

    private static double? Number(JsonElement element, string name, string where) =>
        !element.TryGetProperty(name, out var value) || value.ValueKind == JsonValueKind.Null ? null
        : value.ValueKind == JsonValueKind.Number && double.IsFinite(value.GetDouble()) ? value.GetDouble()
        : throw new MarkException($"{where}: \"{name}\" must be a number");

    private static int? Whole(JsonElement element, string name, string where) =>
        Number(element, name, where) is { } v
            ? v == Math.Floor(v) && v is >= 0 and <= int.MaxValue ? (int)v : throw new MarkException(string.Create(CultureInfo.InvariantCulture, $"{where}: {name} {v:G6} must be a whole number"))
            : null;

    private static (double X, double Y)? Pair(JsonElement element, string name, string where)
    {
        if (!element.TryGetProperty(name, out var value) || value.ValueKind == JsonValueKind.Null)
        {
            return null;
        }

        return value.ValueKind == JsonValueKind.Array && value.GetArrayLength() == 2 && value.EnumerateArray().All(v => v.ValueKind == JsonValueKind.Number && double.IsFinite(v.GetDouble()))
            ? (value[0].GetDouble(), value[1].GetDouble())
            : throw new MarkException($"{where}: \"{name}\" must be [x, y] in mm");
    }
}
