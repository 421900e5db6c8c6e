using LaserEngrave.App.Services;
using LaserEngrave.Core.Jobs;

namespace LaserEngrave.App.Tests.Components;

/// <summary>Undo and redo of the job's settings, on the view-models the page binds.</summary>
public sealed class UndoTests : ComponentTest
{
    [Fact]
    public void Undo_AfterAResize_SizeBack_RedoAgain()
    {
        Assert.True(Main.Job.LoadImage(TestFiles.Asset("qr-code.bmp")));
        Assert.False(Main.UndoCommand.CanExecute(null));
        Main.Job.EditWidth(10);

        Main.Job.EditWidth(5);
        Main.UndoCommand.Execute(null);

        Assert.Equal(10, Main.Job.Job!.Geometry.AchievedWidthMm, 2);
        Assert.True(Main.RedoCommand.CanExecute(null));
        Main.RedoCommand.Execute(null);
        Assert.Equal(5, Main.Job.Job!.Geometry.AchievedWidthMm, 2);
        Assert.False(Main.RedoCommand.CanExecute(null));
    }

    [Fact]
    public void Undo_AfterAPresetAndItsPitch_ProcessAndSizeBackStepByStep()
    {
        OpenQr(widthMm: 10);
        var frequency = Main.Job.LaserFrequencyHz;
        Presets.Selected = ProcessPreset.Examples[1].Name;
        Presets.ApplyCommand.Execute(null);
        Presets.ApplyPitchCommand.Execute(null);
        Assert.Equal(0.82, Main.Job.Job!.Geometry.AchievedWidthMm, 2);

        Main.UndoCommand.Execute(null);
        Assert.Equal(10, Main.Job.Job!.Geometry.AchievedWidthMm, 2);
        Assert.Equal(20000, Main.Job.LaserFrequencyHz);

        Main.UndoCommand.Execute(null);
        Assert.Equal(frequency, Main.Job.LaserFrequencyHz);
    }

    [Fact]
    public void Undo_AfterMovingALayerUp_OrderBackAndTheOpenImageUntouched()
    {
        OpenQr(widthMm: 10);
        Assert.True(Main.Layers.Open(TestFiles.Asset(Path.Combine("jobs", "plate.json"))));
        var order = Main.Layers.Layers.Select(l => l.Name).ToList();

        Main.Layers.Move(1, -1);
        Assert.NotEqual(order, Main.Layers.Layers.Select(l => l.Name));
        Main.UndoCommand.Execute(null);

        Assert.Equal(order, Main.Layers.Layers.Select(l => l.Name));
        Assert.Equal(10, Main.Job.Job!.Geometry.AchievedWidthMm, 2);
        Assert.False(Main.UndoCommand.CanExecute(null));
        Main.RedoCommand.Execute(null);
        Assert.Equal(order[1], Main.Layers.Layers[0].Name);
    }

    [Fact]
    public void Undo_AfterClearingTheLayers_TheyComeBack()
    {
        Assert.True(Main.Layers.Open(TestFiles.Asset(Path.Combine("jobs", "plate.json"))));
        var layers = Main.Layers.Layers;

        Main.Layers.Clear();
        Assert.Empty(Main.Layers.Layers);
        Main.UndoCommand.Execute(null);

        Assert.Equal(layers, Main.Layers.Layers);
    }

    [Fact]
    public void Undo_WhileAMoveHoldsTheJob_Disabled()
    {
        OpenQr(widthMm: 10);
        Main.Job.EditWidth(5);

        using (Main.Activity.Begin(MachineOperation.TestMove("frame")))
        {
            Assert.False(Main.UndoCommand.CanExecute(null));
        }

        Assert.True(Main.UndoCommand.CanExecute(null));
    }

    [Fact]
    public void History_AnotherImageOpened_StartsAnew()
    {
        OpenQr(widthMm: 10);
        Main.Job.EditWidth(5);

        Assert.True(Main.Job.LoadImage(TestFiles.Asset("text-banner.png")));

        Assert.False(Main.UndoCommand.CanExecute(null));
    }
}
