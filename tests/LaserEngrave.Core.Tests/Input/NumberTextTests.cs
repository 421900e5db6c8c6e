using System.Globalization;
using LaserEngrave.Core.Input;
using LaserEngrave.Core.Sweeps;

namespace LaserEngrave.Core.Tests.Input;

/// <summary>One reading of a typed number whatever the computer's language: a decimal point or comma, never a thousands separator.</summary>
public class NumberTextTests
{
    /// <summary>
    /// The number formats of the lab's languages. The build runs with invariant globalization (no ICU data), so each is
    /// the invariant culture with that language's decimal and group separators: what a parser that follows the
    /// current culture would pick up.
    /// </summary>
    public static TheoryData<string> Locales => ["de-DE", "es-AR", "en-US", "fr-FR", "invariant"];

    private static CultureInfo Culture(string name)
    {
        var culture = (CultureInfo)CultureInfo.InvariantCulture.Clone();
        (culture.NumberFormat.NumberDecimalSeparator, culture.NumberFormat.NumberGroupSeparator) = name switch
        {
            "de-DE" or "es-AR" => (",", "."),
            "fr-FR" => (",", "\u202F"),
            "en-US" => (".", ","),
            _ => (".", ","),
        };
        return culture;
    }

    private static T Under<T>(string locale, Func<T> read)
    {
        var before = CultureInfo.CurrentCulture;
        CultureInfo.CurrentCulture = Culture(locale);
        try
        {
            return read();
        }
        finally
        {
            CultureInfo.CurrentCulture = before;
        }
    }

    [Theory]
    [MemberData(nameof(Locales))]
    public void TryParse_PointOrComma_SameValueInEveryLocale(string locale)
    {
        foreach (var (text, expected) in new[] { ("5,5", 5.5), ("5.5", 5.5), ("0,5", 0.5), (",5", 0.5), ("-1,25", -1.25), ("12", 12.0), ("1e3", 1000.0), ("2,5e-3", 0.0025), (" 7,0 ", 7.0), ("-0", 0.0) })
        {
            var (ok, value, problem) = Under(locale, () => (NumberText.TryParse(text, out var v, out var p), v, p));
            Assert.True(ok, $"{locale} '{text}': {problem}");
            Assert.Equal(expected, value);
        }
    }

    [Theory]
    [InlineData("1,000,000", "more than one decimal mark")]
    [InlineData("1.000,5", "more than one decimal mark")]
    [InlineData("1,000.5", "more than one decimal mark")]
    [InlineData("1 000", "is not a number")]
    [InlineData("NaN", "is not a number")]
    [InlineData("Infinity", "is not a number")]
    [InlineData("-∞", "is not a number")]
    [InlineData("", "is empty")]
    [InlineData("5 mm", "is not a number")]
    [InlineData("0x10", "is not a number")]
    [InlineData("1e400", "is too large")]
    public void TryParse_NotOneNumber_RefusedSayingHowToWriteIt(string text, string problem)
    {
        foreach (var locale in new[] { "de-DE", "en-US", "fr-FR" })
        {
            var (ok, said) = Under(locale, () => (NumberText.TryParse(text, out _, out var p), p));
            Assert.False(ok);
            Assert.Contains(problem, said, StringComparison.Ordinal);
        }
    }

    [Theory]
    [InlineData("1,000", "could be 1 or 1000: write 1000 or 1.0")]
    [InlineData("1.000", "could be 1 or 1000: write 1000 or 1.0")]
    [InlineData("10,000", "could be 10 or 10000: write 10000 or 10.0")]
    [InlineData("2,500", "could be 2.5 or 2500: write 2500 or 2.5")]
    [InlineData("-2.500", "could be -2.5 or -2500: write -2500 or -2.5")]
    [InlineData("12.345", "could be 12.345 or 12345: write 12345 or 12.3450")]
    public void TryParse_OneMarkThenThreeDigits_RefusedNamingBothReadings(string text, string problem)
    {
        foreach (var locale in new[] { "de-DE", "es-AR", "en-US", "fr-FR" })
        {
            var (ok, said) = Under(locale, () => (NumberText.TryParse(text, out _, out var p), p));
            Assert.False(ok);
            Assert.Equal(problem, said);
        }
    }

    [Theory]
    [InlineData("0,125", 0.125)]
    [InlineData("0.125", 0.125)]
    [InlineData("12,5", 12.5)]
    [InlineData("1000", 1000.0)]
    [InlineData("1.5", 1.5)]
    [InlineData("1.0", 1.0)]
    [InlineData("12.3450", 12.345)]
    [InlineData("1234,567", 1234.567)]
    [InlineData("1.000e3", 1000.0)]
    public void TryParse_OneReadingOnly_Read(string text, double expected)
    {
        Assert.True(NumberText.TryParse(text, out var value, out var problem), problem);
        Assert.Equal(expected, value);
    }

    [Fact]
    public void TryParsePair_AmbiguousPart_RefusedNamingBothReadings()
    {
        Assert.False(NumberText.TryParsePair("1,000;2", out _, out _, out var said));
        Assert.Equal("X '1,000' could be 1 or 1000: write 1000 or 1.0", said);
    }

    [Theory]
    [InlineData("10,10", 10.0, 10.0)]
    [InlineData("5.5,10.2", 5.5, 10.2)]
    [InlineData("5,5;10,2", 5.5, 10.2)]
    [InlineData("5.5;10", 5.5, 10.0)]
    [InlineData(" 1 , 2 ", 1.0, 2.0)]
    public void TryParsePair_UnambiguousForms_BothNumbers(string text, double x, double y)
    {
        foreach (var locale in new[] { "de-DE", "es-AR", "en-US", "fr-FR" })
        {
            var (ok, px, py) = Under(locale, () => (NumberText.TryParsePair(text, out var a, out var b, out _), a, b));
            Assert.True(ok);
            Assert.Equal((x, y), (px, py));
        }
    }

    [Theory]
    [InlineData("5,5,10,2", "could be read more than one way")]
    [InlineData("5,5,10", "could be read more than one way")]
    [InlineData("5", "expected two numbers")]
    [InlineData("1;2;3", "expected two numbers")]
    [InlineData("5,5;x", "Y 'x' is not a number")]
    public void TryParsePair_AmbiguousOrBroken_RefusedWithHowToWriteIt(string text, string problem)
    {
        Assert.False(NumberText.TryParsePair(text, out _, out _, out var said));
        Assert.Contains(problem, said, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("3", 3L)]
    [InlineData("-2", -2L)]
    public void TryParseWhole_Digits_Read(string text, long expected)
    {
        Assert.True(NumberText.TryParseWhole(text, int.MinValue, int.MaxValue, out var value, out _));
        Assert.Equal(expected, value);
    }

    [Theory]
    [InlineData("1,5", "takes a whole number")]
    [InlineData("1.000", "could be 1 or 1000: write 1000 or 1.0")]
    [InlineData("three", "is not a whole number")]
    [InlineData("99999999999", "is too large")]
    public void TryParseWhole_NotWhole_Refused(string text, string problem)
    {
        Assert.False(NumberText.TryParseWhole(text, int.MinValue, int.MaxValue, out _, out var said));
        Assert.Contains(problem, said, StringComparison.Ordinal);
    }

    [Theory]
    [MemberData(nameof(Locales))]
    public void SweepAxis_DecimalCommasWithSemicolons_SameAsPoints(string locale)
    {
        var points = Under(locale, () => SweepAxis.Parse("speed=0.5,1,2.25", "--rows"));
        var commas = Under(locale, () => SweepAxis.Parse("speed=0,5;1;2,25", "--rows"));
        var range = Under(locale, () => SweepAxis.Parse("focus=-0,5..0,5:0,25", "--rows"));

        Assert.Equal([0.5, 1, 2.25], points.Values);
        Assert.Equal(points.Values, commas.Values);
        Assert.Equal([-0.5, -0.25, 0, 0.25, 0.5], range.Values);
    }
}
