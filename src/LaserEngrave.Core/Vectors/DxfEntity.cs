using System.Globalization;

namespace LaserEngrave.Core.Vectors;

/// <summary>One DXF entity as its group codes: the type, where it starts in the file, and typed access to its values.</summary>
internal sealed class DxfEntity(string file, string type, int line, List<(int Code, string Value, int Line)> groups)
{
    public string Type { get; } = type;

    public int Line { get; } = line;

    public List<(int Code, string Value, int Line)> Groups { get; } = groups;

    private List<DxfEntity>? _children;

    /// <summary>Child entities: a POLYLINE's VERTEXes (made on first use: most entities have none).</summary>
    public List<DxfEntity> Children => _children ??= [];

    public string? Handle => Text(5);

    public string Layer => Text(8) ?? "0";

    /// <summary>How messages name it: type, handle and line.</summary>
    public string Id => Handle is { } h ? $"{Type} (handle {h}, line {Line})" : $"{Type} (line {Line})";

    /// <summary>How warnings name it: its handle, or its line when it has none.</summary>
    public string ShortId => Handle is { } h ? $"handle {h}" : $"line {Line}";

    public string? Text(int code)
    {
        foreach (var g in Groups)
        {
            if (g.Code == code)
            {
                return g.Value;
            }
        }

        return null;
    }

    public double Number(int code, double fallback)
    {
        foreach (var g in Groups)
        {
            if (g.Code == code)
            {
                return Parse(g.Value, g.Line);
            }
        }

        return fallback;
    }

    public double Number(int code) => Groups.Any(g => g.Code == code)
        ? Number(code, 0)
        : throw Error($"has no group code {code}");

    public int Integer(int code, int fallback) => (int)Number(code, fallback);

    /// <summary>Every value of a repeated group code, in order.</summary>
    public List<double> Numbers(int code) => [.. Groups.Where(g => g.Code == code).Select(g => Parse(g.Value, g.Line))];

    public DrawingException Error(string problem) => new($"{file}: {Id}: {problem}");

    public double Parse(string text, int lineNumber)
    {
        if (double.TryParse(text, NumberStyles.Float, CultureInfo.InvariantCulture, out var value) && double.IsFinite(value))
        {
            return value;
        }

        throw new DrawingException($"{file}: {Id}: \"{text}\" on line {lineNumber} is not a number");
    }
}
