using System.Globalization;
using System.Text.Json;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Marks;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Jobs;

/// <summary>
/// A job's layers from a JSON file: <c>{"layers": [{"name": ..., "source": ..., "mode": ..., ...}, ...]}</c>
/// (docs/vectors.md, "Layers"); a source is relative to the file's folder. Unknown or bad values are refused with one line
/// naming the file, the layer and the field. A layer may be a mark, <c>{"mark": { ...a marks file's fields... }}</c>
/// (docs/marking.md): it is made, when the file is read, into its codes' and texts' layers, numbered from the sample counter.
/// </summary>
public static class JobFile
{
    /// <summary>The most layers a job file may have: each is prepared (read, planned and estimated) before anything moves.</summary>
    public const int MaxLayers = 1000;

    private static readonly string[] Fields =
        ["name", "source", "mark", "mode", "drawingLayer", "widthMm", "originMm", "speedMmPerS", "frequencyHz", "passes", "toleranceUm", "fillPitchUm", "thresholdPercent", "dither", "invert", "quarterTurns", "mirrorX", "mirrorY"];

    /// <summary>Reads the job file's layers; its marks, if any, made into their layers with <paramref name="marks"/>.</summary>
    /// <param name="marks">The counter, machine, time and sample a mark layer is made with; a file with a mark layer needs them.</param>
    public static IReadOnlyList<JobLayer> Load(string path, JobMarks? marks = null)
    {
        ArgumentException.ThrowIfNullOrWhiteSpace(path);
        if (IO.RegularFile.Problem(path) is { } problem)
        {
            throw new PlanException($"{path}: {problem}");
        }

        JsonDocument document;
        try
        {
            document = JsonDocument.Parse(IO.TextFile.Read(path), new JsonDocumentOptions { AllowTrailingCommas = true, CommentHandling = JsonCommentHandling.Skip });
        }
        catch (IO.TextEncodingException ex)
        {
            throw new PlanException($"{path}: {ex.Message}", ex);
        }
        catch (JsonException ex)
        {
            throw new PlanException($"{path}: {IO.JsonProblem.Syntax(ex)}", ex);
        }

        using (document)
        {
            var folder = Path.GetDirectoryName(Path.GetFullPath(path)) ?? ".";
            var root = document.RootElement;
            if (root.ValueKind != JsonValueKind.Object || !root.TryGetProperty("layers", out var layers) || layers.ValueKind != JsonValueKind.Array)
            {
                throw new PlanException($"{path}: a job file is an object with \"layers\": [ ... ]");
            }

            foreach (var property in root.EnumerateObject())
            {
                if (property.Name != "layers")
                {
                    throw new PlanException($"{path}: unknown field \"{property.Name}\" (a job file has only \"layers\")");
                }
            }

            if (layers.GetArrayLength() > MaxLayers)
            {
                throw new PlanException($"{path}: {layers.GetArrayLength()} layers, more than the {MaxLayers} a job file may have");
            }

            var list = new List<(JobLayer? Layer, MarkSpec? Mark, int Index, string Where)>();
            var index = 0;
            foreach (var element in layers.EnumerateArray())
            {
                index++;
                list.Add(element.ValueKind == JsonValueKind.Object && element.TryGetProperty("mark", out _)
                    ? ReadMark(path, index, element)
                    : (ReadLayer(path, folder, index, element), null, index, string.Empty));
            }

            return list.Count > 0 ? MakeMarks(path, list, marks) : throw new PlanException($"{path}: \"layers\" is empty");
        }
    }

    // A mark layer has the mark's own fields (a marks file's, read by the same reader) and, beside them, only a name.
    private static (JobLayer? Layer, MarkSpec Mark, int Index, string Where) ReadMark(string path, int index, JsonElement element)
    {
        var where = $"{path}: layer {index}";
        foreach (var property in element.EnumerateObject())
        {
            if (property.Name is not ("mark" or "name"))
            {
                throw new PlanException($"{where}: \"{property.Name}\" beside \"mark\": a mark layer has only \"mark\" (a marks file's fields, originMm and the process among them) and \"name\"");
            }
        }

        var name = String(element, "name", where);
        where = name is null ? $"{where} (mark)" : $"{where} \"{name}\" (mark)";
        try
        {
            return (null, MarkFile.Read(element.GetProperty("mark"), where), index, where);
        }
        catch (MarkException ex)
        {
            throw new PlanException(ex.Message, ex);
        }
    }

    /// <summary>
    /// The job's layers with each mark made into its layers, in <see cref="MarkManifest.MarksFolder"/>: every mark layer
    /// numbers its copies from the same first number (the counter's next, or a resumed run's), so a code and a text elsewhere
    /// carry the same sample's number; the job burns as many numbers as its largest mark has copies.
    /// </summary>
    private static List<JobLayer> MakeMarks(string path, List<(JobLayer? Layer, MarkSpec? Mark, int Index, string Where)> entries, JobMarks? marks)
    {
        var manifest = Path.Combine(MarkManifest.MarksFolder(path), MarkLayout.ManifestFileName);
        if (entries.All(e => e.Mark is null))
        {
            // A record left from when the file had marks must not advance the counter for a run that burns none.
            if (File.Exists(manifest))
            {
                File.Delete(manifest);
            }

            return [.. entries.Select(e => e.Layer!)];
        }

        var firstMark = entries.First(e => e.Mark is not null);
        if (marks is null)
        {
            throw new PlanException($"{path}: layer {firstMark.Index} is a mark, which needs the sample counter; run the file with engrave --job or open it in the app");
        }

        // Counted before a file is made: a hostile file of many large arrays is refused without writing them.
        var planned = entries.Sum(e => e.Mark is { } m ? (long)m.Copies * ((m.Code is null ? 0 : 1) + (m.Code is null || m.Label ? 1 : 0)) : 1);
        if (planned > MaxLayers)
        {
            throw new PlanException($"{path}: its marks would make {planned} layers, more than the {MaxLayers} a job may have; make fewer copies");
        }

        int first;
        try
        {
            first = marks.FirstNumber ?? new MarkCounter(marks.CounterPath).Next();
        }
        catch (MarkException ex)
        {
            throw new PlanException($"{path}: {ex.Message}", ex);
        }

        var context = new MarkContext(0, marks.Sample, marks.Now, marks.Profile.Name);
        var layers = new List<JobLayer>();
        var placed = new List<PlacedMark>();
        var count = 0;
        foreach (var (layer, mark, index, where) in entries)
        {
            if (mark is null)
            {
                layers.Add(layer!);
                continue;
            }

            try
            {
                var layout = MarkLayout.Make(mark, first, context, marks.Profile, Path.Combine(MarkManifest.MarksFolder(path), $"layer-{index}"));
                layers.AddRange(layout.Layers);
                placed.AddRange(layout.Marks);
                count = Math.Max(count, mark.Copies);
            }
            catch (MarkException ex)
            {
                throw new PlanException($"{where}: {ex.Message}", ex);
            }
        }

        MarkManifest.Write(manifest, new MarkManifest(Path.GetFullPath(marks.CounterPath), first, count, placed, marks.Now));
        return layers;
    }

    /// <summary>
    /// Writes the layers as a job file that <see cref="Load"/> reads back the same: sources relative to the file's folder
    /// (with forward slashes), fields left at their defaults left out.
    /// </summary>
    /// <exception cref="IOException">The file cannot be written.</exception>
    public static void Save(string path, IReadOnlyList<JobLayer> layers)
    {
        ArgumentException.ThrowIfNullOrWhiteSpace(path);
        ArgumentNullException.ThrowIfNull(layers);
        var full = Path.GetFullPath(path);
        var bytes = ToJson(layers, Path.GetDirectoryName(full) ?? ".");

        // Written whole beside the file, then moved over it: a failed save leaves the old job as it was.
        var temporary = full + ".saving";
        File.WriteAllBytes(temporary, bytes);
        File.Move(temporary, full, overwrite: true);
    }

    /// <summary>
    /// The job file's bytes (UTF-8 JSON), as <see cref="Save"/> writes them: sources relative to <paramref name="folder"/>,
    /// or, with null, full paths, for a file whose folder is not known (one the browser downloads, then uploads back).
    /// </summary>
    public static byte[] ToJson(IReadOnlyList<JobLayer> layers, string? folder)
    {
        ArgumentNullException.ThrowIfNull(layers);
        using var buffer = new MemoryStream();
        using (var json = new Utf8JsonWriter(buffer, new JsonWriterOptions { Indented = true }))
        {
            json.WriteStartObject();
            json.WriteStartArray("layers");
            foreach (var layer in layers)
            {
                json.WriteStartObject();
                json.WriteString("name", layer.Name);
                var source = Path.GetFullPath(layer.Source);
                json.WriteString("source", (folder is null ? source : Path.GetRelativePath(folder, source)).Replace('\\', '/'));
                json.WriteString("mode", layer.Mode.ToString().ToLowerInvariant());
                if (layer.DrawingLayer is { } drawingLayer)
                {
                    json.WriteString("drawingLayer", drawingLayer);
                }

                Optional(json, "widthMm", layer.WidthMm);
                json.WriteStartArray("originMm");
                json.WriteNumberValue(layer.Origin.X);
                json.WriteNumberValue(layer.Origin.Y);
                json.WriteEndArray();
                Optional(json, "speedMmPerS", layer.SpeedMmPerS);
                Optional(json, "frequencyHz", layer.FrequencyHz);
                json.WriteNumber("passes", layer.Passes);
                Optional(json, "toleranceUm", layer.ToleranceUm);
                Optional(json, "fillPitchUm", layer.FillPitchUm);
                if (layer.Mask with { QuarterTurns = 0, MirrorX = false, MirrorY = false } != Imaging.MaskOptions.Default)
                {
                    json.WriteNumber("thresholdPercent", layer.Mask.ThresholdPercent);
                    json.WriteString("dither", Imaging.DitherNames.Name(layer.Mask.Dither));
                    json.WriteBoolean("invert", layer.Mask.Invert);
                }

                if (layer.Mask.QuarterTurns != 0)
                {
                    json.WriteNumber("quarterTurns", layer.Mask.QuarterTurns);
                }

                if (layer.Mask.MirrorX)
                {
                    json.WriteBoolean("mirrorX", true);
                }

                if (layer.Mask.MirrorY)
                {
                    json.WriteBoolean("mirrorY", true);
                }
                json.WriteEndObject();
            }

            json.WriteEndArray();
            json.WriteEndObject();
        }

        buffer.WriteByte((byte)'\n');
        return buffer.ToArray();

        static void Optional(Utf8JsonWriter json, string name, double? value)
        {
            if (value is { } v)
            {
                json.WriteNumber(name, v);
            }
        }
    }

    private static JobLayer ReadLayer(string path, string folder, int index, JsonElement element)
    {
        var where = $"{path}: layer {index}";
        if (element.ValueKind != JsonValueKind.Object)
        {
            throw new PlanException($"{where}: must be an object");
        }

        foreach (var property in element.EnumerateObject())
        {
            if (!Fields.Contains(property.Name, StringComparer.Ordinal))
            {
                throw new PlanException($"{where}: unknown field \"{property.Name}\" (fields: {string.Join(", ", Fields)})");
            }
        }

        var name = String(element, "name", where) ?? $"layer {index}";
        where = $"{path}: layer {index} \"{name}\"";
        var source = String(element, "source", where) ?? throw new PlanException($"{where}: \"source\" (the image or drawing file) is missing");
        var mode = String(element, "mode", where) is { } text
            ? text.Trim().ToLowerInvariant() switch
            {
                "raster" => LayerMode.Raster,
                "outline" => LayerMode.Outline,
                "fill" => LayerMode.Fill,
                "both" => LayerMode.Both,
                _ => throw new PlanException($"{where}: mode \"{text}\" is not raster, outline, fill or both"),
            }
            : Vectors.DrawingReader.IsDrawing(source) ? LayerMode.Outline : LayerMode.Raster;
        var passes = Number(element, "passes", where) is { } p
            ? p != Math.Floor(p) ? throw new PlanException($"{where}: passes {N(p)} must be a whole number 1..{JobSpec.MaxPasses}")
            : JobRules.Passes((int)Math.Clamp(p, int.MinValue, int.MaxValue)) is { } rule ? throw new PlanException($"{where}: passes {N(p)}: {rule}")
            : (int)p
            : 1;
        return new JobLayer
        {
            Name = name,
            Source = Path.GetFullPath(Path.Combine(folder, source)),
            Mode = mode,
            DrawingLayer = String(element, "drawingLayer", where),
            WidthMm = Positive(element, "widthMm", where),
            Origin = Origin(element, where),
            SpeedMmPerS = Positive(element, "speedMmPerS", where),
            FrequencyHz = Positive(element, "frequencyHz", where),
            Passes = passes,
            ToleranceUm = Positive(element, "toleranceUm", where),
            FillPitchUm = Positive(element, "fillPitchUm", where),
            Mask = Mask(element, where),
        };
    }

    private static Imaging.MaskOptions Mask(JsonElement element, string where)
    {
        var threshold = Number(element, "thresholdPercent", where) is { } t
            ? JobRules.Threshold(t) is { } rule ? throw new PlanException($"{where}: thresholdPercent {N(t)}: {rule}") : t
            : Imaging.MaskOptions.Default.ThresholdPercent;
        var ditherText = String(element, "dither", where);
        var dither = Imaging.DitherNames.Parse(ditherText, out var unknown);
        if (unknown)
        {
            throw new PlanException($"{where}: dither \"{ditherText}\" is not {Imaging.DitherNames.List}");
        }

        var turns = Number(element, "quarterTurns", where) is { } q
            ? q is 0 or 1 or 2 or 3 ? (int)q : throw new PlanException($"{where}: quarterTurns {N(q)}: give 0, 1, 2 or 3 (quarter turns clockwise)")
            : 0;
        return new Imaging.MaskOptions
        {
            ThresholdPercent = threshold, Dither = dither, Invert = Flag(element, "invert", where), QuarterTurns = turns,
            MirrorX = Flag(element, "mirrorX", where), MirrorY = Flag(element, "mirrorY", where),
        };
    }

    private static bool Flag(JsonElement element, string name, string where) =>
        !element.TryGetProperty(name, out var value) || value.ValueKind == JsonValueKind.Null ? false
        : value.ValueKind is JsonValueKind.True or JsonValueKind.False ? value.GetBoolean()
        : throw new PlanException($"{where}: \"{name}\" must be true or false");

    private static string? String(JsonElement element, string name, string where) =>
        !element.TryGetProperty(name, out var value) || value.ValueKind == JsonValueKind.Null ? null
        : value.ValueKind == JsonValueKind.String ? value.GetString()
        : throw new PlanException($"{where}: \"{name}\" must be a string");

    private static double? Number(JsonElement element, string name, string where) =>
        !element.TryGetProperty(name, out var value) || value.ValueKind == JsonValueKind.Null ? null
        : value.ValueKind == JsonValueKind.Number ? value.GetDouble()
        : throw new PlanException($"{where}: \"{name}\" must be a number{StringNumberHint(value)}");

    /// <summary>How to write a number given as text ("12,5"): it reads the same in every language only as a JSON number.</summary>
    private static string StringNumberHint(JsonElement value) =>
        value.ValueKind != JsonValueKind.String || value.GetString() is not { } text ? string.Empty
        : Input.NumberText.Ambiguous(text) is { } readings ? $" (\"{text}\" {readings}, without quotes)"
        : Input.NumberText.TryParse(text, out var number, out _) ? $": write {Input.NumberText.Show(number)}, without quotes"
        : string.Empty;

    private static double? Positive(JsonElement element, string name, string where) =>
        Number(element, name, where) is { } v
            ? v > 0 && double.IsFinite(v) ? v : throw new PlanException($"{where}: {name} {N(v)} must be a finite number above 0")
            : null;

    private static OriginMm Origin(JsonElement element, string where)
    {
        if (!element.TryGetProperty("originMm", out var value) || value.ValueKind == JsonValueKind.Null)
        {
            return OriginMm.Zero;
        }

        if (value.ValueKind != JsonValueKind.Array || value.GetArrayLength() != 2 || value.EnumerateArray().Any(v => v.ValueKind != JsonValueKind.Number))
        {
            throw new PlanException($"{where}: \"originMm\" must be [x, y] in mm");
        }

        double x = value[0].GetDouble(), y = value[1].GetDouble();
        return x >= 0 && y >= 0 && double.IsFinite(x) && double.IsFinite(y)
            ? new OriginMm(x, y)
            : throw new PlanException($"{where}: originMm {N(x)}, {N(y)} must not be negative");
    }

    private static string N(double v) => v.ToString("0.######", CultureInfo.InvariantCulture);
}
