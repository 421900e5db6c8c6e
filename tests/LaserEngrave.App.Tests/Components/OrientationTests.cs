using Bunit;
using LaserEngrave.App.Components.Workspace;

namespace LaserEngrave.App.Tests.Components;

/// <summary>Rotate and mirror in the Size panel: the job (an image or a drawing) turns on the stage keeping its size, Undo takes it back, and another file opens upright.</summary>
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
    public void RotateRight_Drawing_ThePlanTurnedAndItsSidesSwapped()
    {
        Assert.True(Main.Job.LoadImage(TestFiles.Asset(Path.Combine("drawings", "hexagons.dxf"))));
        var (width, height) = (Main.Job.Drawing!.Plan.WidthMm, Main.Job.Drawing.Plan.HeightMm);
        var cut = Render<SizePanel>(p => p.Add(c => c.Job, Main.Job));

        cut.Find("#rotate-right").Click();

        Assert.Equal(1, Main.Job.QuarterTurns);
        Assert.Equal(height, Main.Job.Drawing!.Plan.WidthMm, 4);
        Assert.Equal(width, Main.Job.Drawing.Plan.HeightMm, 4);
        Assert.Equal("turned 90° clockwise", cut.Find("#orientation-text").TextContent);
        Assert.Same(Main.Job.Drawing, Main.Job.Engraving!.Parts[0].Drawing);
        Main.UndoCommand.Execute(null);
        Assert.Equal(0, Main.Job.QuarterTurns);
        Assert.Equal(width, Main.Job.Drawing!.Plan.WidthMm, 4);
    }

    [Fact]
    public void Open_AnotherImageAfterATurnAndMirror_OpensUpright()
    {
        Assert.True(Main.Job.LoadImage(TestFiles.Asset("text-banner.png")));
        Main.Job.Rotate(clockwise: true);
        Main.Job.FlipHorizontal();

        Assert.True(Main.Job.LoadImage(TestFiles.Asset("qr-code.bmp")));

        Assert.Equal((0, false, false), (Main.Job.QuarterTurns, Main.Job.MirrorX, Main.Job.MirrorY));
        Assert.Equal((41, 41), (Main.Job.Mask!.Width, Main.Job.Mask.Height));
        Assert.Equal("upright", Render<SizePanel>(p => p.Add(c => c.Job, Main.Job)).Find("#orientation-text").TextContent);
    }

    [Fact]
    public async Task OpenInBackground_ADrawingAfterATurnedImage_OpensUpright()
    {
        Assert.True(Main.Job.LoadImage(TestFiles.Asset("text-banner.png")));
        Main.Job.Rotate(clockwise: false);
        Main.Job.FlipVertical();
        var upright = Core.Vectors.VectorPlanner.Plan(TestFiles.Asset(Path.Combine("drawings", "hexagons.dxf")), new Core.Vectors.VectorOptions(), Main.Job.Profile);

        Assert.True(await Main.Job.LoadImageAsync(TestFiles.Asset(Path.Combine("drawings", "hexagons.dxf")), Xunit.TestContext.Current.CancellationToken));

        Assert.Equal((0, false, false), (Main.Job.QuarterTurns, Main.Job.MirrorX, Main.Job.MirrorY));
        Assert.Equal(upright.WidthMm / upright.HeightMm, Main.Job.Drawing!.Plan.WidthMm / Main.Job.Drawing.Plan.HeightMm, 6);
    }

    [Fact]
    public void Apply_APastJobOfAnotherFileWithItsTurn_OpensWithThatTurn()
    {
        Assert.True(Main.Job.LoadImage(TestFiles.Asset("qr-code.bmp")));
        var past = Main.Job.ToSettings() with { ImagePath = TestFiles.Asset("text-banner.png"), QuarterTurns = 1, MirrorX = true };

        Main.Job.Apply(past);

        Assert.Equal((1, true), (Main.Job.QuarterTurns, Main.Job.MirrorX));
        Assert.Equal((60, 308), (Main.Job.Mask!.Width, Main.Job.Mask.Height));
    }

    [Fact]
    public void Open_TheSameImageAgainOrAFileThatFails_KeepsTheTurn()
    {
        Assert.True(Main.Job.LoadImage(TestFiles.Asset("text-banner.png")));
        Main.Job.Rotate(clockwise: true);

        Assert.True(Main.Job.LoadImage(TestFiles.Asset("text-banner.png")));
        Assert.False(Main.Job.LoadImage(TestFiles.Asset("no-such-image.png")));

        Assert.Equal(1, Main.Job.QuarterTurns);
        Assert.Equal((60, 308), (Main.Job.Mask!.Width, Main.Job.Mask.Height));
    }
}
