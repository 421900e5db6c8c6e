using System.Globalization;

namespace LaserEngrave.Core.Input;

/// <summary>
/// How every number a person types is read, the same on the command line, in the app's fields and in sweep lists:
/// one decimal mark, a point or a comma (<c>5.5</c> or <c>5,5</c>), never a thousands separator, whatever the
/// computer's language. Two numbers (X,Y) are split at a comma when both are written with points, and at a
/// semicolon when either has a decimal comma (<c>5,5;10,2</c>); anything that could be read two ways is refused
/// with a line that says how to write it, so a value is never read ten times too big. One mark followed by exactly three
/// digits after a group a thousands separator could end (<c>1,000</c>, <c>2.500</c>, <c>12.345</c>) is one of them:
/// in Argentina <c>1.000</c> is a thousand, in the US it is one.
/// </summary>
public static class NumberText
{
    /// <summary>How to write a number, for the end of an error line.</summary>
    public const string Hint = "write it like 5.5 or 5,5, without thousands separators";

    /// <summary>How to write two numbers, for the end of an error line.</summary>
    public const string PairHint = "write X,Y with decimal points (5.5,10.2) or X;Y with decimal commas (5,5;10,2)";

    /// <summary>Reads one finite number; <paramref name="problem"/> says what is wrong (without the value) when it is not one.</summary>
    public static bool TryParse(string? text, out double value, out string problem)
    {
        value = 0;
        var t = text?.Trim() ?? string.Empty;
        if (t.Length == 0)
        {
            problem = $"is empty; {Hint}";
            return false;
        }

        var points = t.Count(c => c == '.');
        var commas = t.Count(c => c == ',');
        if (points + commas > 1)
        {
            problem = $"has more than one decimal mark (a thousands separator is never read); {Hint}";
            return false;
        }

        if (Ambiguous(t) is { } readings)
        {
            problem = readings;
            return false;
        }

        // Only digits, a sign, one mark and an exponent: NaN, Infinity and a culture's own symbols are not numbers a person means.
        if (!t.All(c => char.IsAsciiDigit(c) || c is '+' or '-' or '.' or ',' or 'e' or 'E')
            || !double.TryParse(t.Replace(',', '.'), NumberStyles.AllowLeadingSign | NumberStyles.AllowDecimalPoint | NumberStyles.AllowExponent, CultureInfo.InvariantCulture, out var v))
        {
            problem = $"is not a number; {Hint}";
            return false;
        }

        if (!double.IsFinite(v))
        {
            problem = "is too large";
            return false;
        }

        // -0 reads as 0: a sign on nothing would only show up as "-0" in messages and logs.
        value = v == 0 ? 0 : v;
        problem = string.Empty;
        return true;
    }

    /// <summary>Reads a whole number within <paramref name="min"/>..<paramref name="max"/> (no decimal mark, no separator); <paramref name="problem"/> says what is wrong.</summary>
    public static bool TryParseWhole(string? text, long min, long max, out long value, out string problem)
    {
        value = 0;
        var t = text?.Trim() ?? string.Empty;
        if (Ambiguous(t) is { } readings)
        {
            problem = readings;
            return false;
        }

        if (!t.All(c => char.IsAsciiDigit(c) || c is '+' or '-') || !t.Any(char.IsAsciiDigit))
        {
            problem = t.Contains(',') || t.Contains('.')
                ? "takes a whole number, like 3 (no decimal mark, no thousands separator)"
                : "is not a whole number, like 3";
            return false;
        }

        if (!long.TryParse(t, NumberStyles.AllowLeadingSign, CultureInfo.InvariantCulture, out var v) || v < min || v > max)
        {
            problem = "is too large";
            return false;
        }

        value = v;
        problem = string.Empty;
        return true;
    }

    /// <summary>Reads two numbers, X,Y (points) or X;Y (points or commas); refuses <c>5,5,10,2</c>, which could be read two ways.</summary>
    public static bool TryParsePair(string? text, out double x, out double y, out string problem)
    {
        x = y = 0;
        var t = text?.Trim() ?? string.Empty;
        var parts = t.Contains(';') ? t.Split(';') : t.Split(',');
        if (parts.Length != 2)
        {
            problem = t.Contains(';') || t.Count(c => c == ',') < 2 ? $"expected two numbers; {PairHint}" : $"could be read more than one way; {PairHint}";
            return false;
        }

        if (!TryParse(parts[0], out x, out var px))
        {
            problem = $"X '{parts[0].Trim()}' {px}";
            return false;
        }

        if (!TryParse(parts[1], out y, out var py))
        {
            problem = $"Y '{parts[1].Trim()}' {py}";
            return false;
        }

        problem = string.Empty;
        return true;
    }

    /// <summary>
    /// Splits a list of numbers: at semicolons when it has any (so each value may have a decimal comma, <c>0,5;1;2</c>),
    /// else at commas (<c>0.5,1,2</c>).
    /// </summary>
    public static string[] SplitList(string text)
    {
        ArgumentNullException.ThrowIfNull(text);
        return text.Contains(';') ? text.Split(';') : text.Split(',');
    }

    /// <summary>
    /// The two readings of a number that could be either (one mark after 1-3 digits not starting with 0, then exactly
    /// three digits and nothing else: <c>1,000</c>, <c>2.500</c>), as the problem to show; null when it has one reading.
    /// </summary>
    /// <remarks><c>0,125</c> is not one (no thousands group starts with 0), nor <c>12,5</c>, <c>1000</c> or <c>1.0e3</c>.</remarks>
    public static string? Ambiguous(string? text)
    {
        var t = text?.Trim() ?? string.Empty;
        var body = t.Length > 0 && t[0] is '+' or '-' ? t[1..] : t;
        var mark = body.IndexOfAny(['.', ',']);
        if (mark is < 1 or > 3 || body.Length != mark + 4 || body[0] == '0' || !body.Remove(mark, 1).All(char.IsAsciiDigit))
        {
            return null;
        }

        var sign = t.Length > body.Length && t[0] == '-' ? "-" : string.Empty;
        var whole = sign + body.Remove(mark, 1);
        var fraction = body[(mark + 1)..].TrimEnd('0');

        // The decimal reading written so it cannot be read two ways: 1.0, 2.5, 12.3450.
        var asDecimal = sign + body[..mark] + "." + (fraction.Length == 0 ? "0" : fraction.Length == 3 ? fraction + "0" : fraction);
        var small = sign + body[..mark] + (fraction.Length == 0 ? string.Empty : "." + fraction);
        return $"could be {small} or {whole}: write {whole} or {asDecimal}";
    }

    /// <summary>A number as messages show it: invariant, short.</summary>
    public static string Show(double value) => value.ToString("0.######", CultureInfo.InvariantCulture);
}
