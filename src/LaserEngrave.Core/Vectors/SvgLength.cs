using System.Globalization;

namespace LaserEngrave.Core.Vectors;

/// <summary>SVG lengths: a number with an optional unit, in CSS pixels (96 per inch) or millimetres.</summary>
internal static class SvgLength
{
    public const double MmPerPx = 25.4 / 96;

    /// <summary>CSS pixels in one unit; null for a unit that depends on fonts or the viewport.</summary>
    public static double? PxPerUnit(string unit) => unit switch
    {
        "" or "px" => 1,
        "mm" => 96 / 25.4,
        "cm" => 96 / 2.54,
        "q" => 96 / 25.4 / 4,
        "in" => 96,
        "pt" => 96 / 72.0,
        "pc" => 16,
        _ => null,
    };

    /// <summary>Splits "12.5mm" into 12.5 and "mm"; false when it is not a number followed by letters or %.</summary>
    public static bool TrySplit(string? text, out double value, out string unit)
    {
        value = 0;
        unit = string.Empty;
        if (text is null)
        {
            return false;
        }

        var s = text.Trim();
        var end = s.Length;
        while (end > 0 && (char.IsLetter(s[end - 1]) || s[end - 1] == '%'))
        {
            end--;
        }

        unit = s[end..].ToLowerInvariant();
        return double.TryParse(s.AsSpan(0, end), NumberStyles.Float, CultureInfo.InvariantCulture, out value) && double.IsFinite(value);
    }

    /// <summary>A length attribute in user units (CSS pixels), or <paramref name="fallback"/> when absent.</summary>
    /// <param name="percentOf">What 100% is, in user units (the viewport's width or height); null where a percentage is not taken.</param>
    public static double UserUnits(string? text, double fallback, string element, string attribute, double? percentOf = null)
    {
        if (text is null)
        {
            return fallback;
        }

        if (TrySplit(text, out var value, out var unit) && PxPerUnit(unit) is { } px)
        {
            return value * px;
        }

        if (percentOf is { } whole && unit == "%" && TrySplit(text, out value, out _))
        {
            return value / 100 * whole;
        }

        throw new DrawingException($"{element}: {attribute}=\"{text}\" is not a length in px, mm, cm, in, pt or pc");
    }
}
