using Bunit;
using LaserEngrave.App.Components.Workspace;
using LaserEngrave.App.Services;
using NSubstitute;

namespace LaserEngrave.App.Tests.Components;

public sealed class PresetsPanelTests : ComponentTest
{
    private IRenderedComponent<PresetsPanel> RenderPanel() => Render<PresetsPanel>(p => p.Add(c => c.Presets, Presets));

    [Fact]
    public void Examples_ThePapersSettingsOffered()
    {
        var cut = RenderPanel();

        var options = cut.FindAll("#preset option").Select(o => o.TextContent).ToList();

        Assert.Contains(options, o => o.Contains("1 kHz", StringComparison.Ordinal) && o.Contains("000", StringComparison.Ordinal));
        Assert.Contains(options, o => o.Contains("20 kHz 150 µJ", StringComparison.Ordinal));
        Assert.Contains("1000 Hz · burn 1 mm/s", cut.Find("#preset-values").TextContent, StringComparison.Ordinal);
    }

    [Fact]
    public void Apply_Paper001_JobTakesItsProcess()
    {
        OpenQr();
        var cut = RenderPanel();
        cut.Find("#preset").Change(ProcessPreset.Examples[1].Name);

        cut.Find("#preset-apply").Click();

        Assert.Equal((20000.0, 2.0, 20.0), (Main.Job.LaserFrequencyHz, Main.Job.BurnSpeedMmPerS, Main.Job.PitchUm));
        Assert.NotNull(Main.Job.Job);
    }

    [Fact]
    public void SaveCurrent_Named_KeptInTheLibrary()
    {
        Main.Job.LaserFrequencyHz = 5000;
        var cut = RenderPanel();
        Assert.True(Disabled(cut.Find("#preset-save")));

        cut.Find("#preset-name").Change("glass");
        cut.Find("#preset-save").Click();

        PresetStore.Received(1).Save(Arg.Is<IReadOnlyList<ProcessPreset>>(l => l.Any(p => p.Name == "glass" && p.LaserFrequencyHz == 5000)));
        Assert.Equal("glass", Presets.Selected);
        Assert.Contains("5000 Hz", cut.Find("#preset-values").TextContent, StringComparison.Ordinal);
    }

    [Fact]
    public void Import_ExportedLibrary_RoundTrips_BadFileRefused()
    {
        var json = Presets.ExportJson();
        Presets.Import(json.Replace("paper 000", "copy", StringComparison.Ordinal));
        var cut = RenderPanel();

        Assert.Equal(3, Presets.Presets.Count);
        Assert.False(Presets.Import("""[{"name":"x","passes":0}]"""));
        cut.WaitForAssertion(() => Assert.Contains("out of range", cut.Find("#preset-error").TextContent, StringComparison.Ordinal));
        Assert.Equal(3, Presets.Presets.Count);
        Assert.StartsWith("data:application/json;base64,", cut.Find("#preset-export").GetAttribute("href"), StringComparison.Ordinal);
    }
}
