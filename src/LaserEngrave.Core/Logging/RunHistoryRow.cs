using System.Globalization;
using System.Text;
using System.Text.Json;
using LaserEngrave.Core.Jobs;

namespace LaserEngrave.Core.Logging;

/// <summary>
/// One logged run as a line of the lab notebook: what the app's history table shows and what the CSV and JSON exports
/// (the app's and <c>laserengrave log list --csv</c>) hold, read from its run log.
/// </summary>
/// <param name="Path">The run log's JSON file.</param>
/// <param name="Source">The image's or drawing's file name; for a job of layers, the job file's name.</param>
/// <param name="Kind">image, dots, drawing or layers.</param>
/// <param name="PitchUm">Pixel pitch, µm, of an image (or dots); null for a drawing or a job of layers, which have none of their own.</param>
public sealed record RunHistoryRow(
    string Path,
    DateTimeOffset StartedAt,
    string? SampleId,
    string Source,
    string Kind,
    double WidthMm,
    double HeightMm,
    double OriginXMm,
    double OriginYMm,
    double? PitchUm,
    double BurnSpeedMmPerS,
    double LaserFrequencyHz,
    int Passes,
    RunOutcome Outcome,
    double ActualSeconds,
    double EstimatedSeconds,
    string? Notes)
{
    /// <summary>The columns in export order, as the CSV's first line names them.</summary>
    public static IReadOnlyList<string> Columns { get; } =
    [
        "started", "sample ID", "image or drawing", "kind", "width mm", "height mm", "origin X mm", "origin Y mm", "pitch µm",
        "burn speed mm/s", "laser frequency Hz", "passes", "outcome", "duration s", "estimate s", "notes", "log",
    ];

    /// <summary>The row of the run in <paramref name="record"/>, logged at <paramref name="path"/>.</summary>
    public static RunHistoryRow From(string path, RunRecord record)
    {
        ArgumentNullException.ThrowIfNull(record);
        var g = record.Geometry;
        var kind = record.Layers is { Count: > 0 } ? "layers"
            : record.Drawing is not null ? "drawing"
            : record.Process.Mode == Planning.PlanMode.Dots ? "dots"
            : "image";
        var source = record.Layers is { Count: > 0 } layers
            ? record.JobFile is { } file ? System.IO.Path.GetFileName(file.Path) : $"{layers.Count} layers"
            : System.IO.Path.GetFileName(record.Image.Path);
        return new RunHistoryRow(
            path, record.StartedAt, record.SampleId, source, kind, g.WidthMm, g.HeightMm, g.OriginXMm, g.OriginYMm, kind is "image" or "dots" ? g.PitchUm : null,
            record.Process.BurnSpeedMmPerS, record.Process.LaserFrequencyHz, record.Passes, record.Outcome, record.ActualSeconds,
            record.EstimatedSeconds, record.Notes)
        {
            Timing = RunSummaryText.Timing(record),
        };
    }

    /// <summary>The late switchings and timing doubts gone on from, as the summary says them (<see cref="RunSummaryText.Timing"/>); null when none.</summary>
    public string? Timing { get; init; }

    /// <summary>The rows of every readable entry, in the entries' order (unreadable logs are left out: the history lists them with their error).</summary>
    public static IReadOnlyList<RunHistoryRow> From(IEnumerable<RunLogEntry> entries) =>
        [.. (entries ?? throw new ArgumentNullException(nameof(entries))).Where(e => e.Record is not null).Select(e => From(e.Path, e.Record!))];

    /// <summary>The process in one line, as the table shows it: "1 mm/s · 1000 Hz · 50 µm".</summary>
    public string ProcessText => string.Create(CultureInfo.InvariantCulture, $"{BurnSpeedMmPerS:0.###} mm/s · {LaserFrequencyHz:0.###} Hz{(PitchUm is { } pitch ? $" · {pitch:0.##} µm" : string.Empty)}");

    /// <summary>Whether the row holds <paramref name="text"/> in its sample ID, file, kind, outcome, notes or date (any case); an empty search matches all.</summary>
    public bool Matches(string? text) => string.IsNullOrWhiteSpace(text)
        || new[] { SampleId, Source, Kind, Outcome.ToString(), Notes, StartedAt.ToString("yyyy-MM-dd HH:mm", CultureInfo.InvariantCulture) }
            .Any(field => field?.Contains(text.Trim(), StringComparison.OrdinalIgnoreCase) == true);

    /// <summary>
    /// The rows as CSV for a spreadsheet: with a decimal point, fields between commas; with a decimal comma (as Excel
    /// reads numbers in German or French), fields between semicolons, so Excel opens either in columns with numbers it
    /// can sum. Dates as yyyy-MM-dd HH:mm:ss.
    /// </summary>
    /// <remarks>The app runs with invariant globalization, so the decimal mark is the user's choice (or the browser's), not the culture's.</remarks>
    public static string ToCsv(IEnumerable<RunHistoryRow> rows, bool decimalComma)
    {
        ArgumentNullException.ThrowIfNull(rows);
        var culture = (CultureInfo)CultureInfo.InvariantCulture.Clone();
        culture.NumberFormat.NumberDecimalSeparator = decimalComma ? "," : ".";
        var separator = decimalComma ? ";" : ",";
        var text = new StringBuilder();
        text.AppendJoin(separator, Columns.Select(c => Field(c, separator))).Append("\r\n");
        foreach (var row in rows)
        {
            string[] fields =
            [
                row.StartedAt.ToString("yyyy-MM-dd HH:mm:ss", CultureInfo.InvariantCulture), Text(row.SampleId), Text(row.Source), row.Kind,
                N(row.WidthMm), N(row.HeightMm), N(row.OriginXMm), N(row.OriginYMm), row.PitchUm is { } pitch ? N(pitch) : string.Empty, N(row.BurnSpeedMmPerS), N(row.LaserFrequencyHz),
                row.Passes.ToString(culture), row.Outcome.ToString().ToLowerInvariant(), N(row.ActualSeconds, "0.#"), N(row.EstimatedSeconds, "0.#"),
                Text(row.Notes), Text(row.Path),
            ];
            text.AppendJoin(separator, fields.Select(f => Field(f, separator))).Append("\r\n");
        }

        return text.ToString();

        string N(double value, string format = "0.######") => value.ToString(format, culture);

        // What the user typed is never taken as a formula by the spreadsheet (=, +, -, @ lead one).
        static string Text(string? value) => value is { Length: > 0 } && "=+-@".Contains(value[0], StringComparison.Ordinal) ? "'" + value : value ?? string.Empty;
    }

    /// <summary>The rows as a JSON array, numbers invariant, the same fields as the CSV under camelCase names.</summary>
    public static string ToJson(IEnumerable<RunHistoryRow> rows)
    {
        ArgumentNullException.ThrowIfNull(rows);
        using var buffer = new MemoryStream();
        using (var json = new Utf8JsonWriter(buffer, new JsonWriterOptions { Indented = true }))
        {
            json.WriteStartArray();
            foreach (var row in rows)
            {
                json.WriteStartObject();
                json.WriteString("startedAt", row.StartedAt);
                json.WriteString("sampleId", row.SampleId);
                json.WriteString("source", row.Source);
                json.WriteString("kind", row.Kind);
                json.WriteNumber("widthMm", row.WidthMm);
                json.WriteNumber("heightMm", row.HeightMm);
                json.WriteNumber("originXMm", row.OriginXMm);
                json.WriteNumber("originYMm", row.OriginYMm);
                if (row.PitchUm is { } pitch)
                {
                    json.WriteNumber("pitchUm", pitch);
                }
                else
                {
                    json.WriteNull("pitchUm");
                }

                json.WriteNumber("burnSpeedMmPerS", row.BurnSpeedMmPerS);
                json.WriteNumber("laserFrequencyHz", row.LaserFrequencyHz);
                json.WriteNumber("passes", row.Passes);
                json.WriteString("outcome", row.Outcome.ToString().ToLowerInvariant());
                json.WriteNumber("actualSeconds", row.ActualSeconds);
                json.WriteNumber("estimatedSeconds", row.EstimatedSeconds);
                json.WriteString("notes", row.Notes);
                json.WriteString("log", row.Path);
                json.WriteEndObject();
            }

            json.WriteEndArray();
        }

        return Encoding.UTF8.GetString(buffer.ToArray()) + "\n";
    }

    // A field with the separator, a quote or a line break is quoted, its quotes doubled (RFC 4180).
    private static string Field(string value, string separator) =>
        value.Contains(separator, StringComparison.Ordinal) || value.IndexOfAny(['"', '\r', '\n']) >= 0
            ? "\"" + value.Replace("\"", "\"\"", StringComparison.Ordinal) + "\""
            : value;
}
