using Bunit;
using LaserEngrave.App.Components.Workspace;
using LaserEngrave.App.ViewModels;

namespace LaserEngrave.App.Tests.Components;

public sealed class NumberFieldTests : ComponentTest
{
    [Fact]
    public void Change_Number_CommittedWithItsValue()
    {
        double? committed = null;
        var cut = Render<NumberField>(p => p.Add(c => c.Id, "w").Add(c => c.Label, "Width").Add(c => c.Unit, "mm").Add(c => c.OnCommit, v => committed = v));

        cut.Find("input").Change("12.5");

        Assert.Equal(12.5, committed);
        Assert.Contains("mm", cut.Find(".unit").TextContent, StringComparison.Ordinal);
    }

    [Fact]
    public void Change_NotANumber_MessageBesideAndNothingCommitted()
    {
        var commits = 0;
        var cut = Render<NumberField>(p => p.Add(c => c.Id, "w").Add(c => c.Label, "Width").Add(c => c.OnCommit, _ => commits++));

        cut.Find("input").Change("12,5 mm");

        Assert.Equal(0, commits);
        Assert.Contains("is not a number", cut.Find("[data-error=w]").TextContent, StringComparison.Ordinal);
        Assert.Equal("true", cut.Find("input").GetAttribute("aria-invalid"));
    }
}

public sealed class ImagePanelTests : ComponentTest
{
    [Fact]
    public void NoImage_HintAndSamplesOffered()
    {
        var cut = Render<ImagePanel>(p => p.Add(c => c.Job, Main.Job).Add(c => c.Samples, Main.SampleImages));

        Assert.NotNull(cut.Find("#no-image"));
        Assert.Equal(2, cut.FindAll("#samples button").Count);
    }

    [Fact]
    public void ScanOffsetTestClicked_AsksForThePatternAndShowsItsError()
    {
        var asked = 0;
        var cut = Render<ImagePanel>(p => p.Add(c => c.Job, Main.Job).Add(c => c.Samples, Main.SampleImages)
            .Add(c => c.OnScanOffsetPattern, () => asked++).Add(c => c.PatternError, "the scan offset pattern could not be written: disk full"));

        cut.Find("#scan-offset-pattern").Click();

        Assert.Equal(1, asked);
        Assert.Equal("the scan offset pattern could not be written: disk full", cut.Find("#pattern-error").TextContent);
    }

    [Fact]
    public void SampleClicked_ImageOpenAndMaskCounted()
    {
        var cut = Render<ImagePanel>(p => p.Add(c => c.Job, Main.Job).Add(c => c.Samples, Main.SampleImages));

        cut.Find("#samples button[data-path$='qr-code.bmp']").Click();

        cut.WaitForAssertion(() => Assert.Contains("41 × 41 px", cut.Find("#image-meta").TextContent, StringComparison.Ordinal));
        Assert.Equal("563", cut.Find("#burn-pixels").TextContent);
    }

    [Fact]
    public void InvertTicked_ViewModelInvertsTheMask()
    {
        OpenQr();
        var cut = Render<ImagePanel>(p => p.Add(c => c.Job, Main.Job));

        cut.Find("#invert").Change(true);

        Assert.True(Main.Job.Invert);
        cut.WaitForAssertion(() => Assert.Equal((41 * 41 - 563).ToString(System.Globalization.CultureInfo.InvariantCulture), cut.Find("#burn-pixels").TextContent.Replace(",", "", StringComparison.Ordinal)));
    }
}

public sealed class SizePanelTests : ComponentTest
{
    [Fact]
    public void Width_Typed_HeightFollowsTheAspect()
    {
        OpenQr();
        var cut = Render<SizePanel>(p => p.Add(c => c.Job, Main.Job));

        cut.Find("#widthMm").Change("12");

        cut.WaitForAssertion(() => Assert.Equal("12", cut.Find("#heightMm").GetAttribute("value")));
        Assert.Contains("12 × 12 mm", cut.Find("#size-figures").TextContent, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("widthMm", "1e9", "at most 60 mm")]
    [InlineData("widthMm", "0", "above 0")]
    [InlineData("pitchUm", "5000", "at most 1000 µm")]
    public void Size_BeyondTheMachine_RefusedBesideTheField(string field, string value, string expected)
    {
        OpenQr();
        var cut = Render<SizePanel>(p => p.Add(c => c.Job, Main.Job));

        cut.Find("#" + field).Change(value);

        cut.WaitForAssertion(() => Assert.Contains(expected, cut.Find($"[data-error={field}]").TextContent, StringComparison.Ordinal));
        Assert.Null(Main.Job.Job);
    }

    [Fact]
    public void Origin_OffTheStage_Refused()
    {
        OpenQr();
        var cut = Render<SizePanel>(p => p.Add(c => c.Job, Main.Job));

        cut.Find("#originXMm").Change("-3");

        cut.WaitForAssertion(() => Assert.Contains("must lie on the stage", cut.Find("[data-error=origin]").TextContent, StringComparison.Ordinal));
    }
}

public sealed class ProcessPanelTests : ComponentTest
{
    [Fact]
    public void BurnSpeed_AboveTheStage_RefusedWithItsUnit()
    {
        OpenQr();
        var cut = Render<ProcessPanel>(p => p.Add(c => c.Job, Main.Job));

        cut.Find("#burnSpeedMmPerS").Change("10");

        cut.WaitForAssertion(() => Assert.Contains("above the stage's 4 mm/s", cut.Find("[data-error=burnSpeedMmPerS]").TextContent, StringComparison.Ordinal));
        Assert.Empty(cut.FindAll("#estimate"));
    }

    [Fact]
    public void Passes_Typed_EstimateCoversThemAll()
    {
        OpenQr();
        var cut = Render<ProcessPanel>(p => p.Add(c => c.Job, Main.Job));
        var one = Main.Job.EstimatedSeconds!.Value;

        cut.Find("#passes").Change("3");

        var statistics = Main.Job.Job!.Statistics;
        Assert.Equal(one + (2 * (statistics.EngravingSeconds + statistics.PassSetupSeconds)), Main.Job.EstimatedSeconds!.Value, 6);
        Assert.Contains("est.", cut.Find("#estimate").TextContent, StringComparison.Ordinal);
    }
}
