using Bunit;
using LaserEngrave.App.Components.Workspace;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Jobs;
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
    public void Apply_Paper001OnA10mmQr_ProcessTakenWidthStays10mm_PitchAskedFirst()
    {
        OpenQr(widthMm: 10);
        var cut = RenderPanel();
        cut.Find("#preset").Change(ProcessPreset.Examples[1].Name);

        cut.Find("#preset-apply").Click();

        Assert.Equal("Si(100), 20 kHz 150 µJ (paper 001)", ProcessPreset.Examples[1].Name);
        Assert.Equal((20000.0, 2.0), (Main.Job.LaserFrequencyHz, Main.Job.BurnSpeedMmPerS));
        Assert.Equal(10, Main.Job.Job!.Geometry.AchievedWidthMm, 2);
        Assert.Equal(10, Main.Job.WidthMm);
        var offer = cut.Find("#preset-pitch-offer").TextContent;
        Assert.Contains("pitch of 20 µm", offer, StringComparison.Ordinal);
        Assert.Contains("from 10 × 10 mm to 0.82 × 0.82 mm", offer, StringComparison.Ordinal);

        cut.Find("#preset-pitch-keep").Click();

        Assert.Empty(cut.FindAll("#preset-pitch-offer"));
        Assert.Equal(10, Main.Job.Job!.Geometry.AchievedWidthMm, 2);
    }

    [Fact]
    public void Apply_Paper001ThenItsPitchAccepted_JobResizedToThePitch()
    {
        OpenQr(widthMm: 10);
        var cut = RenderPanel();
        cut.Find("#preset").Change(ProcessPreset.Examples[1].Name);
        cut.Find("#preset-apply").Click();

        cut.Find("#preset-pitch-apply").Click();

        Assert.Equal(20, Main.Job.PitchUm);
        Assert.Equal(0.82, Main.Job.Job!.Geometry.AchievedWidthMm, 2);
        Assert.Empty(cut.FindAll("#preset-pitch-offer"));
    }

    [Fact]
    public void Apply_PresetWithTheJobsPitch_NothingAsked()
    {
        OpenQr();
        Main.Job.EditPitch(ProcessPreset.Examples[1].PitchUm);
        var cut = RenderPanel();
        cut.Find("#preset").Change(ProcessPreset.Examples[1].Name);

        cut.Find("#preset-apply").Click();

        Assert.Empty(cut.FindAll("#preset-pitch-offer"));
        Assert.Equal(20000.0, Main.Job.LaserFrequencyHz);
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
        cut.WaitForAssertion(() => Assert.Contains("not imported: preset \"x\": passes 0: must be 1..100", cut.Find("#preset-error").TextContent, StringComparison.Ordinal));
        Assert.Equal(3, Presets.Presets.Count);
        Assert.StartsWith("data:application/json;base64,", cut.Find("#preset-export").GetAttribute("href"), StringComparison.Ordinal);
    }

    [Fact]
    public async Task Apply_Seed001WithItsPitch_BurnSpeedRefusedBesideItsFieldAndStartDisabled()
    {
        // Seed 001's preset at its 20 µm pitch makes 10 ms pixels, too short for the gate: the engine refuses the job, so
        // the fields say so before Start (which once stayed enabled until the run failed).
        OpenQr(widthMm: 10);
        await ConnectAsync();
        Assert.True(Main.Run.CanStart);
        var cut = RenderPanel();
        var process = Render<ProcessPanel>(p => p.Add(c => c.Job, Main.Job));
        cut.Find("#preset").Change(ProcessPreset.Examples[1].Name);
        cut.Find("#preset-apply").Click();

        cut.Find("#preset-pitch-apply").Click();

        process.WaitForAssertion(() => Assert.Contains("burn speed 2 mm/s: at a pitch of 20 µm a pixel lasts 10 ms at the burn speed, shorter than", process.Find("[data-error=burnSpeedMmPerS]").TextContent, StringComparison.Ordinal));
        Assert.False(Main.Run.CanStart);
        Assert.False(Main.Run.StartCommand.CanExecute(null));

        Main.Job.BurnSpeedMmPerS = 1.5;

        Assert.Empty(Main.Job.Errors);
        Assert.True(Main.Run.CanStart);
    }

    [Fact]
    public void Apply_PresetAboveTheMachine_RefusedByTheJobRulesNothingChanged()
    {
        // A preset once passed with any frequency of 1 Hz or more; the fields then refused it. Now the preset is refused as the fields would.
        Presets.Import("""[{"name":"hot","laserFrequencyHz":200000}]""");
        Assert.Contains("laser frequency 200000 Hz: outside what the laser gate takes, 1..100000 Hz", Presets.Error, StringComparison.Ordinal);
        Assert.DoesNotContain(Presets.Presets, p => p.Name == "hot");
    }
}
