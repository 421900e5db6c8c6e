using System.Globalization;
using System.Text.Json;

namespace LaserEngrave.Core.Marks;

/// <summary>
/// The sample counter, kept with the settings (mark-counter.json): the number the next mark gets. It advances only when
/// a run of marks completes, to past the last number that run burned; an aborted run leaves it, so the same numbers are
/// made again, and a resumed run keeps the numbers it started with (they are in its job's files).
/// </summary>
public sealed class MarkCounter
{
    /// <summary>The file's name in the settings folder.</summary>
    public const string FileName = "mark-counter.json";

    /// <summary>The largest number the counter may reach.</summary>
    public const int MaxNumber = 999_999_999;

    public MarkCounter(string path)
    {
        ArgumentException.ThrowIfNullOrWhiteSpace(path);
        Path = path;
    }

    public string Path { get; }

    /// <summary>The next number: 1 while no run of marks has completed.</summary>
    /// <exception cref="MarkException">The file is not a counter.</exception>
    public int Next()
    {
        if (Directory.Exists(Path))
        {
            throw new MarkException($"{Path}: is a folder, not the sample counter's file");
        }

        if (!File.Exists(Path))
        {
            return 1;
        }

        try
        {
            using var document = JsonDocument.Parse(File.ReadAllText(Path));
            return document.RootElement.ValueKind == JsonValueKind.Object && document.RootElement.TryGetProperty("next", out var next) && next.TryGetInt32(out var n) && n is >= 1 and <= MaxNumber
                ? n
                : throw new MarkException($"{Path}: \"next\" must be a whole number 1..{MaxNumber}");
        }
        catch (JsonException ex)
        {
            throw new MarkException($"{Path}: {IO.JsonProblem.Describe(ex, "sample counter")}", ex);
        }
    }

    /// <summary>After a completed run that burned <paramref name="count"/> numbers from <paramref name="first"/>: the next is past them (never back).</summary>
    /// <returns>The next number now.</returns>
    public int Complete(int first, int count)
    {
        ArgumentOutOfRangeException.ThrowIfLessThan(first, 1);
        ArgumentOutOfRangeException.ThrowIfLessThan(count, 0);
        var next = (int)Math.Min(MaxNumber, Math.Max(Next(), (long)first + count));
        Write(next);
        return next;
    }

    /// <summary>Sets the next number (the technician's own start, e.g. after a new batch of wafers).</summary>
    public void Set(int next)
    {
        Check(next);
        Write(next);
    }

    /// <summary>Refuses a next number out of 1..<see cref="MaxNumber"/> without writing anything (so a refused job leaves the counter).</summary>
    public static void Check(int next)
    {
        if (next is < 1 or > MaxNumber)
        {
            throw new MarkException(string.Create(CultureInfo.InvariantCulture, $"counter {next} must be 1..{MaxNumber}"));
        }
    }

    private void Write(int next)
    {
        var folder = System.IO.Path.GetDirectoryName(System.IO.Path.GetFullPath(Path));
        if (folder is not null)
        {
            Directory.CreateDirectory(folder);
        }

        // Written beside, then moved over: a crash leaves the old number, never half a file.
        var temporary = Path + ".saving";
        File.WriteAllText(temporary, string.Create(CultureInfo.InvariantCulture, $"{{ \"next\": {next} }}\n"));
        File.Move(temporary, Path, overwrite: true);
    }
}
