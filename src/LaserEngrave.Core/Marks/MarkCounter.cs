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
    public int Next() => Read().Next;

    /// <summary>Whether a completed run has burned any of the <paramref name="count"/> numbers from <paramref name="first"/>.</summary>
    /// <remarks>Kept apart from <see cref="Next"/>: a new batch's `--start` moves the counter past numbers no run burned.</remarks>
    /// <exception cref="MarkException">The file is not a counter.</exception>
    public bool Burned(int first, int count) =>
        Read().Burned.Any(r => r.First <= (long)first + count - 1 && first <= r.Last);

    // The file: { "next": N, "burned": [[first, last], ...] }; "burned" is absent in files written before it was kept.
    private (int Next, List<(int First, int Last)> Burned) Read()
    {
        if (Directory.Exists(Path))
        {
            throw new MarkException($"{Path}: is a folder, not the sample counter's file");
        }

        if (!File.Exists(Path))
        {
            return (1, []);
        }

        try
        {
            using var document = JsonDocument.Parse(File.ReadAllText(Path));
            var root = document.RootElement;
            var next = root.ValueKind == JsonValueKind.Object && root.TryGetProperty("next", out var n) && n.TryGetInt32(out var value) && value is >= 1 and <= MaxNumber
                ? value
                : throw new MarkException($"{Path}: \"next\" must be a whole number 1..{MaxNumber}");
            var burned = new List<(int, int)>();
            if (root.TryGetProperty("burned", out var ranges))
            {
                foreach (var range in ranges.ValueKind == JsonValueKind.Array ? ranges.EnumerateArray() : throw new MarkException($"{Path}: \"burned\" must be a list of [first, last] pairs"))
                {
                    burned.Add(range is { ValueKind: JsonValueKind.Array } && range.GetArrayLength() == 2 && range[0].TryGetInt32(out var a) && range[1].TryGetInt32(out var b) && a >= 1 && b >= a
                        ? (a, b)
                        : throw new MarkException($"{Path}: \"burned\" must be a list of [first, last] pairs"));
                }
            }

            return (next, burned);
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
        var (current, burned) = Read();
        var next = (int)Math.Min(MaxNumber, Math.Max(current, (long)first + count));
        if (count > 0)
        {
            burned.Add((first, (int)Math.Min(MaxNumber, (long)first + count - 1)));
        }

        Write(next, burned);
        return next;
    }

    /// <summary>Sets the next number (the technician's own start, e.g. after a new batch of wafers).</summary>
    public void Set(int next)
    {
        Check(next);
        Write(next, Read().Burned);
    }

    /// <summary>Refuses a next number out of 1..<see cref="MaxNumber"/> without writing anything (so a refused job leaves the counter).</summary>
    public static void Check(int next)
    {
        if (next is < 1 or > MaxNumber)
        {
            throw new MarkException(string.Create(CultureInfo.InvariantCulture, $"counter {next} must be 1..{MaxNumber}"));
        }
    }

    private void Write(int next, List<(int First, int Last)> burned)
    {
        var folder = System.IO.Path.GetDirectoryName(System.IO.Path.GetFullPath(Path));
        if (folder is not null)
        {
            Directory.CreateDirectory(folder);
        }

        // Written beside, then moved over: a crash leaves the old number, never half a file.
        var temporary = Path + ".saving";
        // Ranges that touch are merged, so a long series of runs keeps one range.
        var merged = new List<(int First, int Last)>();
        foreach (var range in burned.OrderBy(r => r.First))
        {
            if (merged.Count > 0 && range.First <= (long)merged[^1].Last + 1)
            {
                merged[^1] = (merged[^1].First, Math.Max(merged[^1].Last, range.Last));
            }
            else
            {
                merged.Add(range);
            }
        }

        var ranges = string.Join(", ", merged.Select(r => string.Create(CultureInfo.InvariantCulture, $"[{r.First}, {r.Last}]")));
        File.WriteAllText(temporary, string.Create(CultureInfo.InvariantCulture, $"{{ \"next\": {next}, \"burned\": [{ranges}] }}\n"));
        File.Move(temporary, Path, overwrite: true);
    }
}
