using Bunit;
using LaserEngrave.App.Components.Workspace;
using LaserEngrave.Core.Jobs;
using NSubstitute;

namespace LaserEngrave.App.Tests.Components;

public sealed class LayersPanelTests : ComponentTest
{
    private static string Plate => TestFiles.Asset(Path.Combine("jobs", "plate.json"));

    [Fact]
    public void OpenJob_LayersListedWithEstimatesAndTotal()
    {
        var cut = Render<LayersPanel>(p => p.Add(c => c.Layers, Main.Layers));

        cut.Find("#job-path").Change(Plate);
        cut.Find("#job-open").Click();

        cut.WaitForAssertion(() => Assert.Equal(3, cut.FindAll("#layer-list li").Count));
        Assert.Equal("logo", cut.Find("#layer-2").GetAttribute("data-layer"));
        Assert.Contains("est.", cut.Find("#layer-3-estimate").TextContent, StringComparison.Ordinal);
        Assert.StartsWith("3 layers", cut.Find("#layers-total").TextContent, StringComparison.Ordinal);
        Assert.NotNull(cut.Find("#layer-1-mode"));
        Assert.Empty(cut.FindAll("#layer-2-mode"));
    }

    [Fact]
    public void PassesOutOfRange_LayerNamedInTheErrorAndStartDisabled()
    {
        Main.Layers.Open(Plate);
        var cut = Render<LayersPanel>(p => p.Add(c => c.Layers, Main.Layers));

        cut.Find("#layer-3-passes").Change("101");

        cut.WaitForAssertion(() => Assert.Equal("layer \"cut\": passes 101: must be 1..100 (burns of the plan over the same place)", cut.Find("[data-error=layer-3]").TextContent));
        Assert.Empty(cut.FindAll("#layer-3-estimate"));
        Assert.Contains("a layer cannot run", cut.Find("#layers-error").TextContent, StringComparison.Ordinal);
        Assert.False(Main.Run.CanStart);
    }

    [Fact]
    public void ReorderRenameAndSave_TheFileReadsBackAsTheListShows()
    {
        Main.Layers.Open(Plate);
        var cut = Render<LayersPanel>(p => p.Add(c => c.Layers, Main.Layers));
        var path = Path.Combine(DataFolder.Path, "saved.json");

        cut.Find("#layer-3-up").Click();
        cut.Find("#layer-1-name").Change("engraved marks");
        cut.Find("#layer-2-remove").Click();
        cut.Find("#job-path").Change(path);
        cut.Find("#job-save").Click();

        Assert.Null(Main.Layers.FileError);
        Assert.Equal(["engraved marks", "logo"], JobFile.Load(path).Select(l => l.Name));
    }

    [Fact]
    public void SaveJob_SingleImageNoLayers_SavedAsOneLayerThatOpensBackAsTheJob()
    {
        Assert.True(Main.Job.LoadImage(TestFiles.Asset("qr-code.bmp")));
        Main.Job.EditWidth(6);
        var cut = Render<LayersPanel>(p => p.Add(c => c.Layers, Main.Layers));
        var path = Path.Combine(DataFolder.Path, "single.json");

        cut.Find("#job-path").Change(path);
        cut.Find("#job-save").Click();

        Assert.Null(Main.Layers.FileError);
        var layer = Assert.Single(JobFile.Load(path));
        Assert.Equal(6, layer.WidthMm);
        Assert.Equal("single.json", cut.Find("#job-download").GetAttribute("download"));
        Assert.Equal("api/jobfile", cut.Find("#job-download").GetAttribute("href"));
    }

    [Fact]
    public void OpenJobFile_ChosenInTheBrowser_KeptAsAnUploadAndOpened()
    {
        var uploaded = Path.Combine(DataFolder.Path, "images", "0123456789abcdef", "plate.json");
        Directory.CreateDirectory(Path.GetDirectoryName(uploaded)!);
        JobFile.Save(uploaded, JobFile.Load(Plate));
        Files.SaveUploadAsync("plate.json", Arg.Any<Stream>(), Arg.Any<CancellationToken>(), Arg.Any<Action?>()).Returns(uploaded);
        var cut = Render<LayersPanel>(p => p.Add(c => c.Layers, Main.Layers));

        cut.FindComponent<Microsoft.AspNetCore.Components.Forms.InputFile>().UploadFiles(InputFileContent.CreateFromText(File.ReadAllText(uploaded), "plate.json"));

        cut.WaitForAssertion(() => Assert.Equal(3, cut.FindAll("#layer-list li").Count));
        Assert.Equal(Path.GetFullPath(uploaded), Main.Layers.JobPath);
    }

    [Fact]
    public void Array_ThreeByOne_ThreeLayersListedAndStartRunsThem()
    {
        Assert.True(Main.Job.LoadImage(TestFiles.Asset("qr-code.bmp")));
        var cut = Render<LayersPanel>(p => p.Add(c => c.Layers, Main.Layers));

        cut.Find("#array-rows").Change("1");
        cut.Find("#array-columns").Change("3");
        cut.Find("#array-pitch-x").Change("7,5");
        cut.Find("#layer-array-add").Click();

        cut.WaitForAssertion(() => Assert.Equal(3, cut.FindAll("#layer-list li").Count));
        Assert.Equal(Main.Job.OriginXMm + 15, Main.Layers.Layers[2].Origin.X, 6);
        Assert.True(Main.Run.RunsLayers);
    }
}
