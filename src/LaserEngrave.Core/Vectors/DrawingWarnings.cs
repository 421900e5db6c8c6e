namespace LaserEngrave.Core.Vectors;

/// <summary>Collects what a reader skipped or could not honour, so nothing is dropped without a word.</summary>
/// <remarks>Skipped entity types are counted and named once each, with the first few ids, rather than one line per entity.</remarks>
public sealed class DrawingWarnings
{
    private const int IdsShown = 5;

    private readonly SortedDictionary<string, (int Count, List<string> Ids)> _skipped = new(StringComparer.Ordinal);
    private readonly List<string> _notes = [];

    /// <summary>Records one skipped entity or element of type <paramref name="type"/>, with an id such as a DXF handle or an SVG id.</summary>
    public void Skipped(string type, string? id, string why)
    {
        var key = $"{type}: {why}";
        if (!_skipped.TryGetValue(key, out var entry))
        {
            entry = (0, []);
        }

        if (id is not null && entry.Ids.Count < IdsShown)
        {
            entry.Ids.Add(id);
        }

        _skipped[key] = (entry.Count + 1, entry.Ids);
    }

    /// <summary>Records a one-off note (units assumed, clipping ignored ...), once.</summary>
    public void Note(string message)
    {
        if (!_notes.Contains(message))
        {
            _notes.Add(message);
        }
    }

    public IReadOnlyList<string> ToList()
    {
        var list = new List<string>(_notes);
        foreach (var (key, (count, ids)) in _skipped)
        {
            var split = key.IndexOf(": ", StringComparison.Ordinal);
            var type = key[..split];
            var why = key[(split + 2)..];
            var named = ids.Count == 0 ? string.Empty : $" ({string.Join(", ", ids)}{(count > ids.Count ? ", ..." : string.Empty)})";
            list.Add($"{count} {type}{named} skipped: {why}");
        }

        return list;
    }
}
