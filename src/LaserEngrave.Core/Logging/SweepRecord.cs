using System.Globalization;
using System.Text;
using System.Text.Encodings.Web;
using System.Text.Json;
using LaserEngrave.Core.Jobs;

namespace LaserEngrave.Core.Logging;

/// <summary>The log of a parameter sweep: the grid, and every cell's values, position and run record (docs/run-log.md).</summary>
public sealed record SweepRecord
{
    public const int CurrentSchemaVersion = 1;

    public int SchemaVersion { get; init; } = CurrentSchemaVersion;

    public required string SoftwareVersion { get; init; }

    public required DateTimeOffset StartedAt { get; init; }

    public required DateTimeOffset EndedAt { get; init; }

    /// <summary>Completed when every cell (and the labels) completed; otherwise how the first that did not ended.</summary>
    public required RunOutcome Outcome { get; init; }

    public string? Fault { get; init; }

    /// <summary>square, lines, dots or image.</summary>
    public required string Pattern { get; init; }

    /// <summary>The image file each cell burned with the image pattern; null otherwise.</summary>
    public string? CellImage { get; init; }

    public required double CellMm { get; init; }

    public required double SpacingMm { get; init; }

    /// <summary>The grid's top-left corner (the labels' when there are labels), mm.</summary>
    public required double OriginXMm { get; init; }

    public required double OriginYMm { get; init; }

    /// <summary>What varies down the rows, as the command line says it: <c>speed=0.5,1,2</c>.</summary>
    public required string Rows { get; init; }

    /// <summary>What varies across the columns; null: one column.</summary>
    public string? Columns { get; init; }

    public bool Simulated { get; init; }

    public string? Notes { get; init; }

    public string? SampleId { get; init; }

    /// <summary>Every cell in the order planned (row by row), run or not.</summary>
    public required IReadOnlyList<SweepCellRecord> Cells { get; init; }

    /// <summary>The labels' run (null without labels, or when the sweep stopped before them).</summary>
    public RunRecord? Labels { get; init; }

    public static string Serialize(SweepRecord record)
    {
        ArgumentNullException.ThrowIfNull(record);
        return JsonSerializer.Serialize(record, Context.SweepRecord);
    }

    /// <summary>Parses a sweep log; throws <see cref="RunLogException"/> with one line naming <paramref name="source"/>.</summary>
    public static SweepRecord Deserialize(string json, string source)
    {
        ArgumentNullException.ThrowIfNull(json);
        try
        {
            return JsonSerializer.Deserialize(json, Context.SweepRecord) ?? throw new RunLogException($"{source}: not a sweep log: it holds null");
        }
        catch (JsonException ex)
        {
            throw new RunLogException($"{source}: {IO.JsonProblem.Describe(ex, "sweep log")}", ex);
        }
    }

    /// <summary>The text summary beside the JSON: the grid, then one line a cell.</summary>
    public static string Format(SweepRecord record)
    {
        ArgumentNullException.ThrowIfNull(record);
        var c = CultureInfo.InvariantCulture;
        var text = new StringBuilder();
        text.AppendLine(string.Create(c, $"LaserEngrave sweep, {record.StartedAt:yyyy-MM-dd HH:mm:ss zzz}{(record.Simulated ? " (simulator)" : string.Empty)}"));
        text.AppendLine(string.Create(c, $"Outcome:  {record.Outcome.ToString().ToLowerInvariant()}{(record.Fault is null ? string.Empty : ": " + record.Fault)}"));
        text.AppendLine(string.Create(c, $"Grid:     {record.Pattern}{(record.CellImage is null ? string.Empty : $" ({record.CellImage})")} cells of {record.CellMm:0.###} mm, {record.SpacingMm:0.###} mm apart, from {record.OriginXMm:0.###}, {record.OriginYMm:0.###} mm"));
        text.AppendLine($"Rows:     {record.Rows}");
        text.AppendLine($"Columns:  {record.Columns ?? "(one)"}");
        if (record.SampleId is not null)
        {
            text.AppendLine($"Sample:   {record.SampleId}");
        }

        if (record.Notes is not null)
        {
            text.AppendLine($"Notes:    {record.Notes}");
        }

        text.AppendLine();
        text.AppendLine("row col  parameters                                at (mm)          size (mm)      outcome    pulses/pixel min/mean/max");
        foreach (var cell in record.Cells)
        {
            var parameters = string.Join(", ", cell.Parameters.Select(p => string.Create(c, $"{p.Key} {p.Value:0.######}")));
            var ppp = cell.Run?.Simulation?.PulsesPerPixel is { } p ? string.Create(c, $"{p.Min}/{p.Mean:0.#}/{p.Max}") : "-";
            var outcome = cell.Run?.Outcome.ToString().ToLowerInvariant() ?? "not run";
            var focus = cell.ZReachedMicrosteps is { } z ? string.Create(c, $"  Z at {z}") : string.Empty;
            if (cell.Run?.Simulation?.Focus is { } f)
            {
                focus += string.Create(c, $" (simulated: Z {f.ZMinMicrosteps}..{f.ZMaxMicrosteps} while firing, {f.LaserOnWhileZMoving} firing while Z moved, defocus {f.DefocusUm:0.#} µm{(f.SpotDiameterUm is { } d ? $", spot {d:0.#} µm" : string.Empty)})");
            }

            text.AppendLine(string.Create(c, $"{cell.Row + 1,3} {cell.Column + 1,3}  {parameters,-40}  {cell.OriginXMm,7:0.###}, {cell.OriginYMm,7:0.###}  {cell.WidthMm:0.###} x {cell.HeightMm:0.###}  {outcome,-9}  {ppp}{focus}"));
        }

        return text.ToString();
    }

    private static readonly RunLogJsonContext Context = new(new JsonSerializerOptions(RunLogJsonContext.Default.Options)
    {
        Encoder = JavaScriptEncoder.UnsafeRelaxedJsonEscaping,
        TypeInfoResolver = null,
    });
}

/// <summary>One cell of a sweep in its log: grid place, the values it was given, where it is on the stage, and its run (null when not run).</summary>
public sealed record SweepCellRecord(
    int Row,
    int Column,
    IReadOnlyDictionary<string, double> Parameters,
    double OriginXMm,
    double OriginYMm,
    double WidthMm,
    double HeightMm,
    double PitchUm,
    int Passes,
    RunRecord? Run)
{
    /// <summary>The absolute Z position planned for the cell, microsteps; null when the sweep does not vary the focus.</summary>
    public long? FocusZMicrosteps { get; init; }

    /// <summary>Where the Z axis said it arrived before the cell burned, microsteps; null when Z did not move for it.</summary>
    public long? ZReachedMicrosteps { get; init; }
}
