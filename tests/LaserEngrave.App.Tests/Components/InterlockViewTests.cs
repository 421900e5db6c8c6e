using Bunit;
using LaserEngrave.App.Components.Workspace;
using LaserEngrave.App.Services;

namespace LaserEngrave.App.Tests.Components;

/// <summary>The interlock in the views: while something holds the machine the job's inputs and the machine's buttons wait.</summary>
public sealed class InterlockViewTests : ComponentTest
{
    [Fact]
    public void Run_UnderWay_JobInputsDisabledWithTheReasonThenEnabledAgain()
    {
        OpenQr();
        var size = Render<SizePanel>(p => p.Add(c => c.Job, Main.Job));
        var process = Render<ProcessPanel>(p => p.Add(c => c.Job, Main.Job));
        var image = Render<ImagePanel>(p => p.Add(c => c.Job, Main.Job).Add(c => c.Samples, Main.SampleImages));
        var presets = Render<PresetsPanel>(p => p.Add(c => c.Presets, Presets));
        Assert.False(Disabled(size.Find("#widthMm")));

        using (Main.Activity.Begin(MachineOperation.Run))
        {
            size.WaitForAssertion(() => Assert.True(Disabled(size.Find("#widthMm"))));
            Assert.All(size.FindAll("input"), i => Assert.True(Disabled(i)));
            Assert.Contains("a run is under way", size.Find("[data-locked]").TextContent, StringComparison.Ordinal);
            process.WaitForAssertion(() => Assert.All(process.FindAll("input, select"), i => Assert.True(Disabled(i))));
            image.WaitForAssertion(() => Assert.All(image.FindAll("#samples button, #thresholdPercent, #dither, #invert"), i => Assert.True(Disabled(i))));
            presets.WaitForAssertion(() => Assert.True(Disabled(presets.Find("#preset-apply"))));
        }

        size.WaitForAssertion(() => Assert.False(Disabled(size.Find("#widthMm"))));
        Assert.Empty(size.FindAll("[data-locked]"));
        presets.WaitForAssertion(() => Assert.False(Disabled(presets.Find("#preset-apply"))));
    }

    [Fact]
    public void Edit_RacingTheLock_RefusalShownAndTheCircuitLives()
    {
        OpenQr();
        var size = Render<SizePanel>(p => p.Add(c => c.Job, Main.Job));
        var input = size.Find("#widthMm");

        using (Main.Activity.Begin(MachineOperation.Homing))
        {
            // The change was sent before the page saw the lock: refused with the line, never thrown at the renderer.
            input.Change("7");
        }

        size.WaitForAssertion(() => Assert.Contains("homing is under way", size.Find("[data-refused]").TextContent, StringComparison.Ordinal));
        Assert.NotEqual(7, Main.Job.WidthMm);
    }

    [Fact]
    public async Task Machine_Connected_ConnectDisabled_HomingHoldsEveryMachineButton()
    {
        var machine = Render<MachinePanel>(p => p.Add(c => c.Machine, Main.Machine));
        var jog = Render<JogPad>(p => p.Add(c => c.Moves, Main.TestMoves).Add(c => c.Machine, Main.Machine));
        Assert.False(Disabled(machine.Find("#connect")));
        await ConnectAsync();
        machine.WaitForAssertion(() => Assert.True(Disabled(machine.Find("#connect"))));
        Assert.False(Disabled(machine.Find("#home")));

        using (Main.Activity.Begin(MachineOperation.Homing))
        {
            machine.WaitForAssertion(() => Assert.True(Disabled(machine.Find("#home"))));
            Assert.True(Disabled(machine.Find("#disconnect")) && Disabled(machine.Find("#identify")));
            jog.WaitForAssertion(() => Assert.True(Disabled(jog.Find("[id='jog-x+']"))));
            Assert.True(Disabled(jog.Find("#goto")));
            Assert.False(Disabled(jog.Find("#jog-stop")));
        }

        machine.WaitForAssertion(() => Assert.False(Disabled(machine.Find("#home"))));
        jog.WaitForAssertion(() => Assert.True(Disabled(jog.Find("#jog-stop"))));
    }
}
