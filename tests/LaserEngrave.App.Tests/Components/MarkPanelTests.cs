using Bunit;
using LaserEngrave.App.Components.Workspace;
using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Marks;
using NSubstitute;

namespace LaserEngrave.App.Tests.Components;

/// <summary>The Mark panel over its view-model: fields, the twin's verdict beside the estimate, and the job opened in Layers.</summary>
public sealed class MarkPanelTests : ComponentTest
{
    private IRenderedComponent<MarkPanel> RenderPanel(MarkViewModel? mark = null) => Render<MarkPanel>(p => p.Add(c => c.Mark, mark ?? Marks));

    [Fact]
    public void Render_Defaults_TenDataMatrixIdsNumberedFromOne()
    {
        var cut = RenderPanel();

        Assert.Equal("S-{n:000}", cut.Find("#mark-text").GetAttribute("value"));
        Assert.Equal("2", cut.Find("#mark-size").GetAttribute("value"));
        Assert.Contains("Next free number: 1", cut.Find("#mark-counter").TextContent, StringComparison.Ordinal);
    }

    [Fact(Timeout = 120_000)]
    public async Task Make_TwoSmallIds_EveryCodeReadsOnTheTwinAndTheJobOpensInLayers()
    {
        var cut = RenderPanel();
        cut.Find("#mark-size").Change("1");
        cut.Find("#mark-copies").Change("2");
        cut.Find("#mark-columns").Change("2");

        cut.Find("#mark-make").Click();
        await Marks.MakeCommand.ExecutionTask!;

        cut.WaitForAssertion(() => Assert.Contains("all 2 codes read on the twin", cut.Find("#mark-verdict").TextContent, StringComparison.Ordinal));
        Assert.Contains("2 marks, estimate", cut.Find("#mark-estimate").TextContent, StringComparison.Ordinal);
        Assert.Equal(["Data Matrix \"S-001\"", "text \"S-001\"", "Data Matrix \"S-002\"", "text \"S-002\""], Main.Layers.Layers.Select(l => l.Name));
        Assert.Empty(cut.FindAll("#mark-error"));
    }

    [Fact]
    public void Make_CodeTooSmallForTheSpot_ShowsTheReasonAndOpensNothing()
    {
        var cut = RenderPanel();
        cut.Find("#mark-size").Change("0,15");

        cut.Find("#mark-make").Click();

        cut.WaitForAssertion(() => Assert.Contains("smaller than the spot", cut.Find("#mark-error").TextContent, StringComparison.Ordinal));
        Assert.Empty(Main.Layers.Layers);
    }

    [Fact]
    public void Make_ACodeThatDoesNotRead_SaysWhichAndOpensNothing()
    {
        var service = Substitute.For<IMarkService>();
        service.NextNumber().Returns(7);
        service.MakeAsync(Arg.Any<MarkSpec>(), Arg.Any<string?>(), true, Arg.Any<CancellationToken>())
            .Returns(new MarkResult(null, [], 12, [new Simulator.Marks.ReadabilityVerdict("S-007", false, null, 20, 20, 100, 144, 40, 10, 10)]));
        var opened = 0;
        var cut = RenderPanel(new MarkViewModel(service, _ => ++opened > 0));

        cut.Find("#mark-make").Click();

        cut.WaitForAssertion(() => Assert.Contains("\"S-007\" does not read on the twin (100 of 144 modules right)", cut.Find("#mark-verdict").TextContent, StringComparison.Ordinal));
        Assert.Equal(0, opened);
        Assert.Contains("Next free number: 7", cut.Find("#mark-counter").TextContent, StringComparison.Ordinal);
    }

    [Fact]
    public void Make_DataFolderCannotBeWritten_SaidInThePanel()
    {
        var service = Substitute.For<IMarkService>();
        service.MakeAsync(Arg.Any<MarkSpec>(), Arg.Any<string?>(), true, Arg.Any<CancellationToken>())
            .Returns<Task<MarkResult>>(_ => throw new IOException("No space left on device"));
        var cut = RenderPanel(new MarkViewModel(service, _ => true));

        cut.Find("#mark-make").Click();

        cut.WaitForAssertion(() => Assert.Equal("the marks could not be saved: No space left on device", cut.Find("#mark-error").TextContent));
    }

    [Fact]
    public void Make_CopiesNotWhole_IsRefusedInOneLine()
    {
        var cut = RenderPanel();
        cut.Find("#mark-copies").Change("2,5");

        cut.Find("#mark-make").Click();

        Assert.Contains("copies 2.5 must be a whole number", cut.Find("#mark-error").TextContent, StringComparison.Ordinal);
    }

    [Fact]
    public void Make_CodeSizeZero_RefusedByMarkLayoutsRuleInThePanelsWords()
    {
        // The panel keeps no ranges of its own: the rule is MarkLayout's (the command line's), named as the panel's box.
        var cut = RenderPanel();
        cut.Find("#mark-size").Change("0");

        cut.Find("#mark-make").Click();

        cut.WaitForAssertion(() => Assert.Equal("code size 0 must be above 0 and at most 100 mm", cut.Find("#mark-error").TextContent));
        Assert.Empty(Main.Layers.Layers);
    }

    [Fact(Timeout = 120_000)]
    public async Task Make_CopiesLoweredBelowColumns_OneMarkMadeAndSaidInTheSingular()
    {
        var cut = RenderPanel();
        cut.Find("#mark-size").Change("1");
        cut.Find("#mark-copies").Change("1");

        cut.Find("#mark-make").Click();
        await Marks.MakeCommand.ExecutionTask!;

        cut.WaitForAssertion(() => Assert.StartsWith("the code reads on the twin", cut.Find("#mark-verdict").TextContent, StringComparison.Ordinal));
        Assert.StartsWith("1 mark, estimate", cut.Find("#mark-estimate").TextContent, StringComparison.Ordinal);
        Assert.StartsWith("These marks: number 1 ", cut.Find("#mark-made").TextContent, StringComparison.Ordinal);
        Assert.Empty(cut.FindAll("#mark-error"));
    }

    [Fact]
    public void Make_SampleIdInTheLog_TheMarksSampleIsTheLogs()
    {
        var service = Substitute.For<IMarkService>();
        service.NextNumber().Returns(4);
        service.MakeAsync(Arg.Any<MarkSpec>(), Arg.Any<string?>(), true, Arg.Any<CancellationToken>()).Returns(new MarkResult(null, [], 1, []));
        Main.Log.SampleId = "Muestra ñ-01";
        var cut = RenderPanel(new MarkViewModel(service, _ => true, () => Main.Log.SampleId));

        cut.Find("#mark-make").Click();

        Assert.Contains("{sample}: Muestra ñ-01", cut.Find("#mark-sample").TextContent, StringComparison.Ordinal);
        service.Received(1).MakeAsync(Arg.Any<MarkSpec>(), "Muestra ñ-01", true, Arg.Any<CancellationToken>());
    }
}
