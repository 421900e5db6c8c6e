using System.Globalization;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using Microsoft.Extensions.DependencyInjection;
using OpenQA.Selenium;

namespace LaserEngrave.App.Tests.Web;

/// <summary>The Camera panel's Find focus in headless Chromium on the simulator with a Z axis (issue 37).</summary>
public sealed class CameraFocusBrowserTests : BrowserTest
{
    [Fact]
    public void CameraPanel_FindFocusOnTheTwinWithZ_ShowsEveryStepAndOffersTheSharpestZ()
    {
        var profile = MachineProfile.Default with { Z = new ZAxisProfile() };
        var path = Path.Combine(DataFolder, "three-axis.json");
        profile.Save(path);
        Host.Services.GetRequiredService<MainViewModel>().UseProfile(path, profile);
        Driver.ExecuteCdpCommand("Emulation.setDeviceMetricsOverride", new Dictionary<string, object?>
        {
            ["width"] = 1366, ["height"] = 768, ["deviceScaleFactor"] = 1, ["mobile"] = false,
        });
        WaitFor(d => Convert.ToInt64(((IJavaScriptExecutor)d).ExecuteScript("return window.innerHeight;"), CultureInfo.InvariantCulture) == 768, "a 1366 x 768 page");
        Id("connect").Click();
        WaitFor(d => d.FindElement(By.Id("machine-connection")).Text.Contains("simulator", StringComparison.Ordinal), "connected to the simulator");
        SetField("goto-x", "30");
        SetField("goto-y", "30");
        WaitFor(_ => Enabled("goto"), "Go to offered");
        Id("goto").Click();
        WaitFor(d => d.FindElement(By.Id("position")).Text == "X 30.000 · Y 30.000 mm", "the stage at 30, 30 mm");
        Driver.ExecuteScript("document.getElementById('panel-camera').open = true; document.getElementById('panel-camera').scrollIntoView();");
        WaitFor(_ => Enabled("camera-find-focus"), "Find focus offered");

        Id("camera-find-focus").Click();

        WaitFor(d => d.FindElements(By.CssSelector("[data-camera=focus]")).Count == 2 || d.FindElements(By.CssSelector("[data-error=camera]")).Count > 0, "the focus sweep done", 120);
        Assert.Empty(Driver.FindElements(By.CssSelector("[data-error=camera]")).Select(e => e.Text));
        Assert.Equal(13, Driver.FindElements(By.CssSelector("#camera-focus-steps tbody tr")).Count);
        var best = double.Parse(Driver.FindElement(By.CssSelector("#camera-focus-steps tr.best")).GetAttribute("data-focus-step")!, CultureInfo.InvariantCulture);
        Assert.InRange(best, 137 - 50, 137 + 50);
        Assert.StartsWith("Go to sharpest Z (+1", Text("camera-focus-go"), StringComparison.Ordinal);
        Driver.ExecuteScript("document.getElementById('camera-focus').scrollIntoView({ block: 'end' });");
        Screenshot("camera-focus");
    }
}
