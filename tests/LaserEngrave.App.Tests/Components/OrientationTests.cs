using Bunit;
using LaserEngrave.App.Components.Workspace;

namespace LaserEngrave.App.Tests.Components;

/// <summary>Rotate and mirror in the Size panel: the job turns on the stage keeping its size, and Undo takes it back.</summary>
public sealed class OrientationTests : ComponentTest
{
    [Fact]
    public void RotateRight_TextBanner_TurnedMaskAndSidesSwapped()
    {
        Assert.True(Main.Job.LoadImage(TestFiles.Asset("text-banner.png")));
        Main.Job.EditWidth(10);
        var height = Main.Job.Job!.Geometry.AchievedHeightMm;
        var cut = Render<SizePanel>(p => p.Add(c => c.Job, Main.Job));
        Assert.Equal("upright", cut.Find("#orientation-text").TextContent);

        cut.Find("#rotate-right").Click();

        Assert.Equal(1, Main.Job.QuarterTurns);
        Assert.Equal((60, 308), (Main.Job.Mask!.Width, Main.Job.Mask.Height));
        Assert.Equal(height, Main.Job.Job!.Geometry.AchievedWidthMm, 3);
        Assert.Equal(10, Main.Job.Job.Geometry.AchievedHeightMm, 1);
        Assert.Equal("turned 90° clockwise", cut.Find("#orientation-text").TextContent);
        Assert.NotNull(Main.Job.Engraving);
    }

    [Fact]
    public void MirrorThenRotateLeft_UndoneStepByStep()
    {
        Assert.True(Main.Job.LoadImage(TestFiles.Asset("text-banner.png")));
        var upright = Main.Job.Mask!;
        var cut = Render<SizePanel>(p => p.Add(c => c.Job, Main.Job));

        cut.Find("#mirror-x").Click();
        cut.Find("#rotate-left").Click();

        Assert.Equal((3, true), (Main.Job.QuarterTurns, Main.Job.MirrorX));
        Assert.True(Main.Job.Mask!.ContentEquals(Core.Imaging.MaskOrientation.Apply(upright, new Core.Imaging.MaskOptions { QuarterTurns = 3, MirrorX = true })));
        Assert.False(Main.Job.Mask.ContentEquals(Core.Imaging.MaskOrientation.Apply(upright, new Core.Imaging.MaskOptions { QuarterTurns = 3 })));
        Main.UndoCommand.Execute(null);
        Assert.Equal((0, true), (Main.Job.QuarterTurns, Main.Job.MirrorX));
        Main.UndoCommand.Execute(null);
        Assert.Equal((0, false), (Main.Job.QuarterTurns, Main.Job.MirrorX));
        Assert.True(Main.Job.Mask!.ContentEquals(upright));
    }

    [Fact]
    public void Drawing_NoRotateOffered()
    {
        Assert.True(Main.Job.LoadImage(TestFiles.Asset(Path.Combine("drawings", "layers.svg"))));

        var cut = Render<SizePanel>(p => p.Add(c => c.Job, Main.Job));

        Assert.Empty(cut.FindAll("#rotate-right"));
    }
}
