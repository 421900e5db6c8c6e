using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using SkiaSharp;

namespace LaserEngrave.Core.Marks;

/// <summary>Text in an installed system font, filled, drawn by SkiaSharp into a burn mask at a given pitch (a raster layer).</summary>
public static class SystemFontText
{
    /// <summary>Draws <paramref name="text"/> with capitals <paramref name="heightMm"/> high, pixels <paramref name="pitchUm"/> apart.</summary>
    /// <param name="family">An installed font family, e.g. "DejaVu Sans".</param>
    /// <exception cref="MarkException">The font is not installed, a value is out of range, or the picture would be too large.</exception>
    public static BitMask Render(string text, string family, double heightMm, double pitchUm, TextAlign align = TextAlign.Left, double lineSpacing = 1.6)
    {
        ArgumentNullException.ThrowIfNull(text);
        ArgumentException.ThrowIfNullOrWhiteSpace(family);
        if (!(heightMm >= StrokeText.MinHeightMm && heightMm <= StrokeText.MaxHeightMm))
        {
            throw new MarkException(string.Create(CultureInfo.InvariantCulture, $"text height {heightMm:G6} mm must be {StrokeText.MinHeightMm}..{StrokeText.MaxHeightMm} mm"));
        }

        if (!(pitchUm > 0 && double.IsFinite(pitchUm)))
        {
            throw new MarkException(string.Create(CultureInfo.InvariantCulture, $"pitch {pitchUm:G6} µm must be above 0"));
        }

        if (!(lineSpacing >= 1 && lineSpacing <= 10))
        {
            throw new MarkException(string.Create(CultureInfo.InvariantCulture, $"line spacing {lineSpacing:G6} must be 1..10 text heights"));
        }

        var lines = text.Replace("\r\n", "\n", StringComparison.Ordinal).Split('\n');
        if (lines.All(l => l.Trim().Length == 0) || lines.Length > StrokeText.MaxLines)
        {
            throw new MarkException(lines.Length > StrokeText.MaxLines ? $"the text has {lines.Length} lines, more than {StrokeText.MaxLines}" : "the text is empty");
        }

        using var typeface = SKTypeface.FromFamilyName(family);

        // Skia falls back to another font for an unknown family: refused, so what burns is the font that was asked for.
        if (typeface is null || !string.Equals(typeface.FamilyName, family, StringComparison.OrdinalIgnoreCase))
        {
            throw new MarkException($"font \"{family}\" is not installed{(typeface is null || typeface.FamilyName.Length == 0 ? string.Empty : $" (the nearest is \"{typeface.FamilyName}\")")}");
        }

        var heightPx = Units.MmToSteps(heightMm, pitchUm);
        using var font = new SKFont(typeface, 100);
        var capHeight = font.Metrics.CapHeight > 0 ? font.Metrics.CapHeight : 70;
        font.Size = (float)(100 * heightPx / capHeight);
        var widths = lines.Select(l => (double)font.MeasureText(l)).ToArray();
        var descent = Math.Max(0, font.Metrics.Descent);
        var linePx = lineSpacing * heightPx;
        var width = (int)Math.Ceiling(widths.Max()) + 2;
        var height = (int)Math.Ceiling(heightPx + ((lines.Length - 1) * linePx) + descent) + 2;
        if (width < 1 || (long)width * height > 100_000_000)
        {
            throw new MarkException(string.Create(CultureInfo.InvariantCulture, $"the text would be {width} x {height} pixels at {pitchUm:G4} µm; make it smaller"));
        }

        using var bitmap = new SKBitmap(new SKImageInfo(width, height, SKColorType.Gray8, SKAlphaType.Opaque));
        using (var canvas = new SKCanvas(bitmap))
        using (var paint = new SKPaint { Color = SKColors.Black, IsAntialias = true })
        {
            canvas.Clear(SKColors.White);
            for (var i = 0; i < lines.Length; i++)
            {
                var x = 1 + (align switch
                {
                    TextAlign.Center => (widths.Max() - widths[i]) / 2,
                    TextAlign.Right => widths.Max() - widths[i],
                    _ => 0,
                });
                canvas.DrawText(lines[i], (float)x, (float)(1 + heightPx + (i * linePx)), SKTextAlign.Left, font, paint);
            }
        }

        var mask = new BitMask(width, height);
        var pixels = bitmap.GetPixelSpan();
        for (var y = 0; y < height; y++)
        {
            for (var x = 0; x < width; x++)
            {
                // Half-covered pixels burn: the glyph's edge lies on the pixel's centre line.
                mask[x, y] = pixels[(y * bitmap.RowBytes) + x] < 128;
            }
        }

        return mask;
    }
}
