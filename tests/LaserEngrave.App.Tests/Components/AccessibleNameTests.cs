using System.Text.RegularExpressions;
using AngleSharp.Dom;
using Bunit;
using LaserEngrave.App.Components.Pages;

namespace LaserEngrave.App.Tests.Components;

/// <summary>
/// What a screen reader reads and voice control matches: every button's accessible name holds the word it shows, no two
/// buttons share a name, and a choice among chips says which is chosen by more than its colour (issue 36, finding 8).
/// </summary>
public sealed partial class AccessibleNameTests : ComponentTest
{
    /// <summary>The name as the browser computes it for these buttons: aria-label when given (Fluent UI's button sets it from its Title), else the text.</summary>
    private static string Name(IElement button) => button.GetAttribute("aria-label") ?? Visible(button);

    private static string Visible(IElement button) => Spaces().Replace(button.TextContent, " ").Trim();

    [GeneratedRegex(@"\s+")]
    private static partial Regex Spaces();

    [GeneratedRegex(@"\p{L}")]
    private static partial Regex Letter();

    private IReadOnlyList<IElement> Buttons()
    {
        OpenQr();
        Assert.True(Main.Layers.AddCurrent());
        Assert.True(Main.Layers.AddCurrent());
        var cut = Render<Workspace>();
        return [.. cut.FindAll("fluent-button, button")];
    }

    [Fact]
    public void Workspace_EveryButtonWithAWord_ItsNameStartsWithTheWord()
    {
        var wrong = Buttons()
            .Where(b => Letter().IsMatch(Visible(b)) && !Name(b).StartsWith(Visible(b).TrimEnd('…'), StringComparison.OrdinalIgnoreCase))
            .Select(b => $"#{b.Id} shows \"{Visible(b)}\" but is named \"{Name(b)}\"")
            .ToList();

        Assert.True(wrong.Count == 0, string.Join("\n", wrong));
    }

    [Fact]
    public void Workspace_ButtonsOfSymbolsOnly_NamedInWords()
    {
        var unnamed = Buttons()
            .Where(b => Visible(b).Length > 0 && !Letter().IsMatch(Visible(b)) && !Letter().IsMatch(Name(b)))
            .Select(b => $"#{b.Id} \"{Visible(b)}\"")
            .ToList();

        Assert.True(unnamed.Count == 0, string.Join(", ", unnamed));
    }

    [Fact]
    public void Workspace_ButtonNames_NoTwoAlike()
    {
        var twins = Buttons()
            .GroupBy(Name)
            .Where(g => g.Count() > 1)
            .Select(g => $"{g.Count()} buttons named \"{g.Key}\": {string.Join(", ", g.Select(b => "#" + b.Id))}")
            .ToList();

        Assert.True(twins.Count == 0, string.Join("\n", twins));
    }

    [Fact]
    public void Workspace_Tab_ReachesStartAmongTheFirstTenStops()
    {
        OpenQr();
        var cut = Render<Workspace>();

        var stops = cut.FindAll("fluent-button, button, input, select, textarea, a[href], summary").Select(e => e.Id).ToList();

        Assert.InRange(stops.IndexOf("start"), 0, 9);
    }

    [Fact]
    public void JogSteps_TheChosenOnePressed()
    {
        var steps = Buttons().Where(b => b.HasAttribute("data-step")).ToList();

        Assert.NotEmpty(steps);
        Assert.All(steps, s => Assert.Contains(s.GetAttribute("aria-pressed"), new[] { "true", "false" }));
        Assert.Single(steps, s => s.GetAttribute("aria-pressed") == "true");
    }
}
