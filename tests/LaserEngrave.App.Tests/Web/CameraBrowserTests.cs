using LaserEngrave.App.ViewModels;
using Microsoft.Extensions.DependencyInjection;
using OpenQA.Selenium;
using OpenQA.Selenium.Interactions;

namespace LaserEngrave.App.Tests.Web;

/// <summary>The Camera panel in headless Chromium on the simulator: the twin's frames and click to go (issue 37).</summary>
public sealed class CameraBrowserTests : BrowserTest
{
    [Fact]
    public void CameraPanel_OnTheTwin_ShowsTheTwinsFrameAndAClickMovesTheStage()
    {
        Size1280x720();
        Id("connect").Click();
        WaitFor(d => d.FindElement(By.Id("machine-connection")).Text.Contains("simulator", StringComparison.Ordinal), "connected to the simulator");
        // The twin's stage starts at the end of its travel: calibration jogs both ways, so it starts from the middle.
        SetField("goto-x", "30");
        SetField("goto-y", "30");
        WaitFor(_ => Enabled("goto"), "Go to offered");
        Id("goto").Click();
        WaitFor(d => d.FindElement(By.Id("position")).Text == "X 30.000 · Y 30.000 mm", "the stage at 30, 30 mm");
        Driver.ExecuteScript("document.getElementById('panel-camera').open = true; document.getElementById('panel-camera').scrollIntoView();");
        WaitFor(d => d.FindElement(By.Id("camera-image")).GetAttribute("src")?.StartsWith("data:image/png;base64,", StringComparison.Ordinal) == true, "the twin's frame shown");
        Assert.Contains("The simulator's camera", Text("camera-source"), StringComparison.Ordinal);

        Assert.True(Enabled("camera-calibrate"));
        Screenshot("camera-twin");

        // A click right of the image's centre: the stage goes there, laser off.
        var main = Host.Services.GetRequiredService<MainViewModel>();
        var before = main.Machine.XMicrosteps;
        var image = Id("camera-view");
        new Actions(Driver).MoveToElement(image, image.Size.Width / 4, 0).Click().Perform();
        WaitFor(d => d.FindElement(By.Id("camera-goto")).Text.StartsWith("Going to ", StringComparison.Ordinal), "the click sent the stage");
        WaitFor(_ => main.Machine.XMicrosteps != before, "the stage moved");
        Assert.Empty(Driver.FindElements(By.CssSelector("[data-error=camera]")));
    }

    [Fact]
    public void CameraPanel_CalibrateThenMapOnTheTwin_ShowsWhatWasMeasuredAndTheMap()
    {
        Size1280x720();
        Id("connect").Click();
        WaitFor(d => d.FindElement(By.Id("machine-connection")).Text.Contains("simulator", StringComparison.Ordinal), "connected to the simulator");
        SetField("goto-x", "30");
        SetField("goto-y", "30");
        WaitFor(_ => Enabled("goto"), "Go to offered");
        Id("goto").Click();
        WaitFor(d => d.FindElement(By.Id("position")).Text == "X 30.000 · Y 30.000 mm", "the stage at 30, 30 mm");
        Driver.ExecuteScript("document.getElementById('panel-camera').open = true; document.getElementById('panel-camera').scrollIntoView();");
        WaitFor(_ => Enabled("camera-calibrate"), "Calibrate offered");

        Id("camera-calibrate").Click();

        WaitFor(d => d.FindElements(By.CssSelector("[data-camera=calibration]")).Count == 4 || d.FindElements(By.CssSelector("[data-error=camera]")).Count > 0, "calibration measured", 120);
        Assert.Empty(Driver.FindElements(By.CssSelector("[data-error=camera]")).Select(e => e.Text));
        Assert.StartsWith("Calibrated: ", Text("camera-calibration"), StringComparison.Ordinal);

        SetField("camera-map-size", "0.5");
        WaitFor(_ => Enabled("camera-map"), "Map offered");
        Id("camera-map").Click();

        WaitFor(d => d.FindElements(By.Id("camera-map-result")).Count == 1 || d.FindElements(By.CssSelector("[data-error=camera]")).Count > 0, "the map stitched", 120);
        Assert.Empty(Driver.FindElements(By.CssSelector("[data-error=camera]")).Select(e => e.Text));
        Assert.StartsWith("Map: ", Text("camera-map-result"), StringComparison.Ordinal);
        Driver.ExecuteScript("document.getElementById('camera-calibrate').scrollIntoView();");
        Screenshot("camera-twin-calibrated");
    }
}
