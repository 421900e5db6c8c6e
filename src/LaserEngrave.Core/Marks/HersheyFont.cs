using System.Globalization;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Marks;

/// <summary>
/// A single-stroke engraving font in the Hershey .jhf format: each glyph a list of polylines on a grid of font units,
/// y growing down, with its left and right bearings. The shipped font is Hershey's "Futura light" (Fonts/futural.jhf,
/// printable ASCII); Fonts/README.md gives its provenance and terms.
/// </summary>
public sealed class HersheyFont
{
    /// <summary>Font units from the top of a capital to the baseline (F to [ in the .jhf coordinates).</summary>
    public const double CapHeightUnits = 21;

    /// <summary>Where the baseline lies in the .jhf coordinates (the letter '[' less 'R').</summary>
    public const double BaselineUnits = 9;

    private readonly Dictionary<char, HersheyGlyph> _glyphs;

    private HersheyFont(Dictionary<char, HersheyGlyph> glyphs) => _glyphs = glyphs;

    /// <summary>The font shipped with the app (Hershey Futura light, printable ASCII 32..126).</summary>
    public static HersheyFont Default { get; } = LoadDefault();

    /// <summary>Whether <paramref name="c"/> has a glyph.</summary>
    public bool Has(char c) => _glyphs.ContainsKey(c);

    /// <summary>The glyph of <paramref name="c"/>.</summary>
    /// <exception cref="MarkException">The font has no such character.</exception>
    public HersheyGlyph Glyph(char c) =>
        _glyphs.TryGetValue(c, out var glyph)
            ? glyph
            : throw new MarkException($"the engraving font has no '{c}' (U+{(int)c:X4}); it has the printable ASCII characters");

    /// <summary>Reads .jhf text: per glyph a 5-column number, a 3-column count of pairs, then the pairs (bearings first, " R" lifts the pen); long glyphs wrap to following lines.</summary>
    /// <param name="text">The file's text.</param>
    /// <param name="firstCharacter">The character of the first glyph; the following ones are consecutive (32 for the ASCII fonts).</param>
    public static HersheyFont Parse(string text, char firstCharacter = ' ')
    {
        ArgumentNullException.ThrowIfNull(text);
        var lines = text.Replace("\r", string.Empty, StringComparison.Ordinal).Split('\n');
        var glyphs = new Dictionary<char, HersheyGlyph>();
        var character = firstCharacter;
        for (var i = 0; i < lines.Length; i++)
        {
            var line = lines[i];
            if (line.Length == 0)
            {
                continue;
            }

            if (line.Length < 10 || !int.TryParse(line.AsSpan(5, 3), NumberStyles.AllowLeadingWhite, CultureInfo.InvariantCulture, out var pairs) || pairs < 1)
            {
                throw new FormatException($"line {i + 1} of the font is not a glyph header");
            }

            var body = line[8..];
            while (body.Length < 2 * pairs && i + 1 < lines.Length)
            {
                body += lines[++i];
            }

            if (body.Length != 2 * pairs)
            {
                throw new FormatException($"the glyph at line {i + 1} of the font has {body.Length / 2} pairs, not {pairs}");
            }

            glyphs[character++] = ParseGlyph(body);
        }

        return new HersheyFont(glyphs);
    }

    private static HersheyGlyph ParseGlyph(string body)
    {
        var left = body[0] - 'R';
        var right = body[1] - 'R';
        var strokes = new List<IReadOnlyList<DrawingPoint>>();
        var current = new List<DrawingPoint>();
        for (var k = 2; k + 1 < body.Length; k += 2)
        {
            if (body[k] == ' ' && body[k + 1] == 'R')
            {
                Flush();
                continue;
            }

            current.Add(new DrawingPoint(body[k] - 'R' - left, body[k + 1] - 'R'));
        }

        Flush();
        return new HersheyGlyph(right - left, strokes);

        void Flush()
        {
            if (current.Count >= 2)
            {
                strokes.Add(current);
            }

            current = [];
        }
    }

    private static HersheyFont LoadDefault()
    {
        using var stream = typeof(HersheyFont).Assembly.GetManifestResourceStream("LaserEngrave.Core.Marks.Fonts.futural.jhf")
            ?? throw new InvalidOperationException("the engraving font is missing from the build (Marks/Fonts/futural.jhf)");
        using var reader = new StreamReader(stream);
        return Parse(reader.ReadToEnd());
    }
}

/// <summary>One glyph: its advance and its polylines in font units, x from the left bearing, y down (baseline at <see cref="HersheyFont.BaselineUnits"/>).</summary>
public sealed record HersheyGlyph(double AdvanceUnits, IReadOnlyList<IReadOnlyList<DrawingPoint>> Strokes);
