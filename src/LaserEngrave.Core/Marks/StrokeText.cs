using System.Globalization;
using System.Text;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Marks;

/// <summary>A text laid out in the engraving font as strokes, in mm with y down, its box's top left at (0, 0).</summary>
/// <param name="Strokes">The polylines, each burned as one stroke.</param>
/// <param name="WidthMm">The widest line's width.</param>
/// <param name="HeightMm">From the first line's cap top to the last line's baseline.</param>
public sealed record StrokeText(IReadOnlyList<IReadOnlyList<DrawingPoint>> Strokes, double WidthMm, double HeightMm)
{
    /// <summary>The smallest text height, mm: below it the strokes of a letter lie closer than a spot.</summary>
    public const double MinHeightMm = 0.05;

    /// <summary>The largest text height, mm.</summary>
    public const double MaxHeightMm = 100;

    /// <summary>The most lines a text may have.</summary>
    public const int MaxLines = 50;

    /// <summary>Lays <paramref name="text"/> out: capitals <paramref name="heightMm"/> high, lines <paramref name="lineSpacing"/> heights apart (baseline to baseline).</summary>
    /// <exception cref="MarkException">A value is out of range or a character is not in the font.</exception>
    public static StrokeText Layout(string text, double heightMm, TextAlign align = TextAlign.Left, double lineSpacing = 1.6, HersheyFont? font = null)
    {
        ArgumentNullException.ThrowIfNull(text);
        font ??= HersheyFont.Default;
        if (!(heightMm >= MinHeightMm && heightMm <= MaxHeightMm))
        {
            throw new MarkException(string.Create(CultureInfo.InvariantCulture, $"text height {heightMm:G6} mm must be {MinHeightMm}..{MaxHeightMm} mm"));
        }

        if (!(lineSpacing >= 1 && lineSpacing <= 10))
        {
            throw new MarkException(string.Create(CultureInfo.InvariantCulture, $"line spacing {lineSpacing:G6} must be 1..10 text heights"));
        }

        var lines = text.Replace("\r\n", "\n", StringComparison.Ordinal).Split('\n');
        if (text.Length == 0 || lines.All(l => l.Trim().Length == 0))
        {
            throw new MarkException("the text is empty");
        }

        if (lines.Length > MaxLines)
        {
            throw new MarkException($"the text has {lines.Length} lines, more than {MaxLines}");
        }

        var scale = heightMm / HersheyFont.CapHeightUnits;
        var widths = lines.Select(l => l.Sum(c => font.Glyph(c).AdvanceUnits) * scale).ToArray();
        var width = widths.Max();
        var strokes = new List<IReadOnlyList<DrawingPoint>>();
        for (var i = 0; i < lines.Length; i++)
        {
            var x = align switch
            {
                TextAlign.Center => (width - widths[i]) / 2,
                TextAlign.Right => width - widths[i],
                _ => 0,
            };

            // The cap top of the first line is y = 0: the baseline lies one height below it.
            var baseline = heightMm + (i * lineSpacing * heightMm);
            foreach (var c in lines[i])
            {
                var glyph = font.Glyph(c);
                foreach (var stroke in glyph.Strokes)
                {
                    strokes.Add([.. stroke.Select(p => new DrawingPoint(x + (p.X * scale), baseline + ((p.Y - HersheyFont.BaselineUnits) * scale)))]);
                }

                x += glyph.AdvanceUnits * scale;
            }
        }

        return new StrokeText(strokes, width, heightMm + ((lines.Length - 1) * lineSpacing * heightMm));
    }

    /// <summary>The strokes as paths of a drawing, moved by (<paramref name="dx"/>, <paramref name="dy"/>) mm.</summary>
    public IReadOnlyList<DrawingPath> Paths(double dx = 0, double dy = 0, string layer = "text") =>
        [.. Strokes.Select((s, i) => new DrawingPath(
            [.. s.Zip(s.Skip(1), (a, b) => (IDrawingCurve)new LineCurve(new DrawingPoint(a.X + dx, a.Y + dy), new DrawingPoint(b.X + dx, b.Y + dy)))],
            Closed: false,
            layer,
            $"stroke {i + 1}"))];

    /// <summary>The box around the strokes themselves (descenders and accents included), mm.</summary>
    public (DrawingPoint Min, DrawingPoint Max) InkBounds()
    {
        var points = Strokes.SelectMany(s => s).ToList();
        return points.Count == 0
            ? (new DrawingPoint(0, 0), new DrawingPoint(0, 0))
            : (new DrawingPoint(points.Min(p => p.X), points.Min(p => p.Y)), new DrawingPoint(points.Max(p => p.X), points.Max(p => p.Y)));
    }

    /// <summary>Writes the strokes, moved by (<paramref name="dx"/>, <paramref name="dy"/>) mm, as an SVG in millimetres that the drawing reader reads back.</summary>
    public void WriteSvg(string path, double dx = 0, double dy = 0)
    {
        var (_, max) = InkBounds();
        var w = Math.Max(max.X + dx, 0.001);
        var h = Math.Max(max.Y + dy, 0.001);
        var svg = new StringBuilder();
        svg.Append(CultureInfo.InvariantCulture, $"<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w:0.######}mm\" height=\"{h:0.######}mm\" viewBox=\"0 0 {w:0.######} {h:0.######}\">\n");
        foreach (var stroke in Strokes)
        {
            svg.Append("  <path fill=\"none\" stroke=\"black\" d=\"M");
            foreach (var p in stroke)
            {
                svg.Append(CultureInfo.InvariantCulture, $" {p.X + dx:0.######},{p.Y + dy:0.######}");
            }

            svg.Append("\"/>\n");
        }

        svg.Append("</svg>\n");
        File.WriteAllText(path, svg.ToString());
    }
}
