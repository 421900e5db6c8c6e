using System.Text.Json;
using System.Text.Json.Serialization;

namespace LaserEngrave.Core.Marks;

/// <summary>
/// The marks' record beside their job file (marks.json): which counter a completed run advances, from which number and
/// by how many, and every copy's text and place. A run of the job reads it to advance the counter when it completes.
/// </summary>
/// <param name="Counter">The counter file.</param>
/// <param name="FirstNumber">The first copy's number.</param>
/// <param name="Count">How many numbers the job burns.</param>
/// <param name="Marks">Every copy's code and text as placed.</param>
/// <param name="MadeAt">For a job file's marks: when they were made ({date}, {time}), so a resumed run makes them again the same.</param>
public sealed record MarkManifest(string Counter, int FirstNumber, int Count, IReadOnlyList<PlacedMark> Marks, DateTimeOffset? MadeAt = null)
{
    /// <summary>The marks' record's file name, beside the job file: the counter, the first number, and each mark.</summary>
    public const string FileName = "marks.json";

    private static readonly JsonSerializerOptions Options = new()
    {
        PropertyNamingPolicy = JsonNamingPolicy.CamelCase,
        WriteIndented = true,
        DefaultIgnoreCondition = JsonIgnoreCondition.WhenWritingNull,
    };

    public static void Write(string path, MarkManifest manifest) => File.WriteAllText(path, JsonSerializer.Serialize(manifest, Options) + "\n");

    /// <summary>
    /// Where a job file's own marks are made when it is read: the folder <c>NAME.marks</c> beside <c>NAME.json</c>, with a
    /// folder for each mark layer and this record.
    /// </summary>
    public static string MarksFolder(string jobFile)
    {
        var full = Path.GetFullPath(jobFile);
        return Path.Combine(Path.GetDirectoryName(full) ?? ".", Path.GetFileNameWithoutExtension(full) + ".marks");
    }

    /// <summary>
    /// The record of <paramref name="jobFile"/>'s marks: of the marks in the file itself as last read (in
    /// <see cref="MarksFolder"/>), or of the marks `mark` made the job of (beside it); null when the job has no marks.
    /// </summary>
    /// <exception cref="MarkException">The record is there but unreadable.</exception>
    public static MarkManifest? Beside(string jobFile)
    {
        var path = Path.Combine(MarksFolder(jobFile), FileName);
        if (!File.Exists(path))
        {
            path = Path.Combine(Path.GetDirectoryName(Path.GetFullPath(jobFile)) ?? ".", FileName);
        }

        if (!File.Exists(path))
        {
            return null;
        }

        try
        {
            return JsonSerializer.Deserialize<MarkManifest>(File.ReadAllText(path), Options) ?? throw new MarkException($"{path}: empty");
        }
        catch (JsonException ex)
        {
            throw new MarkException($"{path}: {IO.JsonProblem.Describe(ex, "marks record")}", ex);
        }
    }

    /// <summary>After a run of the job beside it: advances the counter when the run completed, and only then.</summary>
    /// <param name="completed">Whether the run completed (its outcome is the log's to say; marks sit below the log).</param>
    /// <param name="logged">The numbers the run's log carries when it has them (a resumed run's); else the record's are used.</param>
    /// <returns>The counter's next number after a completed run; null otherwise.</returns>
    public static int? AfterRun(string jobFile, bool completed, (string Counter, int FirstNumber, int Count)? logged = null) =>
        !completed ? null
        : logged is { } marks ? new MarkCounter(marks.Counter).Complete(marks.FirstNumber, marks.Count)
        : Beside(jobFile) is { } manifest ? new MarkCounter(manifest.Counter).Complete(manifest.FirstNumber, manifest.Count)
        : null;

    /// <summary>
    /// Why the marks of <paramref name="jobFile"/> must not burn (again): a completed run has already burned some of their
    /// numbers (the counter records each completed run's); null when the job has no marks or they are still to burn.
    /// </summary>
    /// <remarks>Two jobs made from the same counter before either burned carry the same numbers: the second is refused once the first completes.</remarks>
    /// <exception cref="MarkException">The record or the counter is unreadable.</exception>
    public static string? BurnedAlready(string jobFile) =>
        Beside(jobFile) is { Count: > 0 } manifest ? BurnedAlready(jobFile, manifest.Counter, manifest.FirstNumber, manifest.Count) : null;

    private static string? BurnedAlready(string what, string counter, int first, int count) =>
        new MarkCounter(counter).Burned(first, count)
            ? string.Create(System.Globalization.CultureInfo.InvariantCulture, $"{what}: its marks carry the numbers {first}..{(long)first + count - 1}, which a completed run has burned already (the counter {counter} records them); make the next ones with laserengrave mark into a new folder (or open the job file of marks again), so no two samples carry one number")
            : null;
}
