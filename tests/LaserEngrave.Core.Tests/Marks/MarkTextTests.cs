using LaserEngrave.Core.Marks;

namespace LaserEngrave.Core.Tests.Marks;

/// <summary>The placeholders of a mark's text.</summary>
public class MarkTextTests
{
    private static readonly MarkContext Context = new(7, "wafer-3", new DateTimeOffset(2026, 11, 27, 9, 5, 0, TimeSpan.FromHours(1)), "Lab A");

    [Theory]
    [InlineData("S-{n:000}", "S-007")]
    [InlineData("{n}", "7")]
    [InlineData("{n:0}", "7")]
    [InlineData("{sample}/{n:00}", "wafer-3/07")]
    [InlineData("{date} {time}", "2026-11-27 09:05")]
    [InlineData("{profile}", "Lab A")]
    [InlineData("{{n}} is {n}", "{n} is 7")]
    [InlineData("plain", "plain")]
    public void Resolve_Placeholders_AreReplaced(string template, string expected)
    {
        Assert.Equal(expected, MarkText.Resolve(template, Context));
    }

    [Theory]
    [InlineData("S-{x}", "unknown placeholder {x}")]
    [InlineData("S-{n", "not closed")]
    [InlineData("S-}", "lone")]
    [InlineData("{n:0000000000}", "unknown placeholder")]
    public void Resolve_BadPlaceholder_IsRefusedNamingIt(string template, string expected)
    {
        var ex = Assert.Throws<MarkException>(() => MarkText.Resolve(template, Context));

        Assert.Contains(expected, ex.Message);
    }

    [Fact]
    public void Resolve_SampleWithoutOne_IsRefused()
    {
        var ex = Assert.Throws<MarkException>(() => MarkText.Resolve("{sample}", Context with { Sample = null }));

        Assert.Contains("needs the run's sample ID", ex.Message);
    }
}
