using Bunit;
using LaserEngrave.App.Components.Pages;
using LaserEngrave.App.Components.Workspace;
using LaserEngrave.App.Services;

namespace LaserEngrave.App.Tests.Components;

/// <summary>The workspace's keyboard shortcuts, as the page's key handler reports them to the stage canvas.</summary>
public sealed class ShortcutTests : ComponentTest
{
    private static Task Press(IRenderedComponent<Workspace> cut, string shortcut) =>
        cut.InvokeAsync(() => cut.FindComponent<StageCanvas>().Instance.OnShortcutKey(shortcut));

    [Fact]
    public async Task F1_Pressed_EveryShortcutListedF1OrEscHidesThem()
    {
        var cut = Render<Workspace>();
        Assert.Empty(cut.FindAll("#help-overlay"));

        await Press(cut, "help");

        var rows = cut.FindAll("#help-keys tr").Select(r => r.QuerySelector("th")!.TextContent.Trim()).ToArray();
        Assert.Equal(["Ctrl+O", "Ctrl+S", "Ctrl+Z", "Ctrl+Y or Ctrl+Shift+Z", "Arrow keys", "Ctrl+arrow keys", "Shift+arrow keys", "Esc", "F1"], rows);
        await Press(cut, "help");
        Assert.Empty(cut.FindAll("#help-overlay"));
        await Press(cut, "help");
        await Press(cut, "escape");
        Assert.Empty(cut.FindAll("#help-overlay"));
    }

    [Fact]
    public async Task Esc_DuringATestMove_StopsIt()
    {
        var cut = Render<Workspace>();
        using var lease = Main.Activity.Begin(MachineOperation.TestMove("frame"));

        await Press(cut, "escape");

        Assert.True(lease.CancellationToken.IsCancellationRequested);
    }

    [Fact]
    public async Task Esc_DuringARunOrASweep_LeavesItAlone()
    {
        var cut = Render<Workspace>();
        foreach (var operation in new[] { MachineOperation.Run, MachineOperation.Sweep })
        {
            using var lease = Main.Activity.Begin(operation);

            await Press(cut, "escape");

            Assert.False(lease.CancellationToken.IsCancellationRequested, operation.Summary);
        }
    }

    [Fact]
    public async Task CtrlS_WithLayers_SavesToTheJobFileField()
    {
        using var folder = TestFiles.NewFolder();
        var path = Path.Combine(folder.Path, "mine.json");
        OpenQr(widthMm: 4);
        var cut = Render<Workspace>();
        Assert.True(Main.Layers.AddCurrent());
        cut.Find("#job-path").Change(path);

        await Press(cut, "save");

        Assert.True(File.Exists(path));
        Assert.Null(Main.Layers.FileError);
        Assert.Equal(path, Main.Layers.JobPath);
    }

    [Fact]
    public async Task CtrlS_SingleImageNoLayers_SavedAsAJobFileOfOneLayer()
    {
        using var folder = TestFiles.NewFolder();
        var path = Path.Combine(folder.Path, "single.json");
        OpenQr(widthMm: 4);
        var cut = Render<Workspace>();
        cut.Find("#job-path").Change(path);

        await Press(cut, "save");

        Assert.Null(Main.Layers.FileError);
        Assert.Equal(4, Assert.Single(LaserEngrave.Core.Jobs.JobFile.Load(path)).WidthMm!.Value, 3);
        Assert.Empty(Main.Layers.Layers);
    }

    [Fact]
    public async Task CtrlS_NothingOpen_SaysWhyInTheOpenedLayersPanel()
    {
        var cut = Render<Workspace>();
        Assert.False(cut.Find("#panel-layers").HasAttribute("open"));

        await Press(cut, "save");

        cut.WaitForAssertion(() => Assert.StartsWith("open an image or drawing first", cut.Find("#layers-file-error").TextContent, StringComparison.Ordinal));
        Assert.True(cut.Find("#panel-layers").HasAttribute("open"));
    }

    [Fact]
    public async Task CtrlZ_UndoesTheLastChange()
    {
        OpenQr(widthMm: 10);
        var cut = Render<Workspace>();
        Main.Job.EditWidth(5);

        await Press(cut, "undo");

        Assert.Equal(10, Main.Job.Job!.Geometry.AchievedWidthMm, 2);
    }
}
