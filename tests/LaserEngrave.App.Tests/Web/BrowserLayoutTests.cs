using System.Globalization;
using LaserEngrave.App.ViewModels;
using LaserEngrave.App.Web;
using LaserEngrave.Devices.Execution;
using Microsoft.AspNetCore.Builder;
using Microsoft.AspNetCore.Hosting;
using Microsoft.AspNetCore.Http;
using Microsoft.AspNetCore.Hosting.Server;
using Microsoft.AspNetCore.Hosting.Server.Features;
using Microsoft.Extensions.DependencyInjection;
using OpenQA.Selenium;
using OpenQA.Selenium.Chrome;
using OpenQA.Selenium.Interactions;
using OpenQA.Selenium.Support.UI;

namespace LaserEngrave.App.Tests.Web;

/// <summary>The workspace's layout, themes, keys, panels and page weight in the browser.</summary>
/// <remarks>Split from <see cref="BrowserTests"/> so that the two halves run side by side.</remarks>
public sealed class BrowserLayoutTests : BrowserTest
{
    [Fact]
    public void Workspace_CommonWindowSizes_NoHorizontalScrolling()
    {
        OpenSample("text-banner.png");
        foreach (var (width, height) in new[] { (1280, 720), (1920, 1080), (1000, 700), (800, 600) })
        {
            Resize(width, height);
            Assert.True(HorizontalOverflow() <= 0, $"at {width} x {height} the page scrolls sideways by {HorizontalOverflow()} px");
            Assert.True(Id("runbar").Displayed && Id("stage-canvas").Displayed);
            // The log folder's Copy beside its path reads whole (it was cut to "C…" at 1280 wide).
            var copyCut = Convert.ToInt64(Driver.ExecuteScript("var b = document.getElementById('copy-log-folder'); return b.scrollWidth - b.clientWidth;"), CultureInfo.InvariantCulture);
            Assert.True(copyCut <= 0, $"at {width} x {height} the log folder's Copy is cut by {copyCut} px");
        }
    }

    [Fact]
    public void Workspace_Laptop1366At125Percent_StageStaysInViewBesideThePanelBeingEdited()
    {
        // 1366 x 768 at 125 % zoom leaves a page of 1093 x 501: every panel was below the stage, which then left the view.
        PageSize(1093, 501);
        OpenSample("text-banner.png");

        const string InView = """
            const r = arguments[0].getBoundingClientRect();
            return r.height > 0 && r.top >= 0 && r.bottom <= window.innerHeight && r.left >= 0 && r.right <= window.innerWidth;
            """;
        foreach (var field in new[] { "widthMm", "notes" })
        {
            Driver.ExecuteScript("arguments[0].scrollIntoView({ block: 'center' });", Id(field));
            Assert.True((bool)Driver.ExecuteScript(InView, Id(field))!, $"#{field} is not in view at 1093 x 501");
            Assert.True((bool)Driver.ExecuteScript(InView, Id("stage-canvas"))!, $"the stage left the view while #{field} is shown at 1093 x 501");
        }

        Screenshot("workspace-1093x501");
        var stage = Id("stage-canvas").Size;
        Assert.True(stage.Width >= 450 && stage.Height >= 250, $"the stage is only {stage.Width} x {stage.Height} px at 1093 x 501");
        Assert.True((bool)Driver.ExecuteScript(InView, Id("start"))!, "Start is off-screen at 1093 x 501");
    }

    [Fact]
    public void Stage_ZoomedInFortyTimes_StopsAtOneMicrometreAPixelAndANewJobComesIntoView()
    {
        OpenSample("qr-code.bmp");
        WaitFor(_ => View().Scale > 1, "the stage drawn");
        for (var i = 0; i < 40; i++)
        {
            Id("zoom-in").Click();
        }

        WaitFor(_ => View().Scale >= 999, "zoomed in to the limit");
        Assert.True(View().Scale <= 1000, $"zoomed to {View().Scale} px/mm, past 1 µm a pixel");

        // Zoomed deep on the QR's middle, the banner opened elsewhere on the stage: the view shows the travel again.
        SetField("originXMm", "40");
        WaitFor(_ => View().Scale < 100, "the view following the job moved out of it");
    }

    [Fact]
    public void Stage_JobClickedThenArrows_TheJobMovesNotTheStageShiftArrowsJog()
    {
        Size1280x720();
        OpenSample("qr-code.bmp");
        Id("connect").Click();
        WaitFor(d => Enabled("jog-x-"), "connected to the simulator");
        WaitFor(_ => Position().Y is not null, "the position read");
        var (_, y0) = Position();
        var x0 = FieldValue("originXMm");
        var (scale, ox, oy) = View();
        var canvas = Id("stage-canvas");

        // A click inside the job's box (1 mm right of its origin and 0.3 mm down) selects it.
        new Actions(Driver).MoveToLocation((int)(canvas.Location.X + ox + ((x0 + 1) * scale)), (int)(canvas.Location.Y + oy + ((FieldValue("originYMm") + 0.3) * scale))).Click().Perform();
        WaitFor(_ => Id("stage-host").GetAttribute("data-selected") == "true", "the job selected");
        new Actions(Driver).SendKeys(Keys.ArrowRight).Perform();
        WaitFor(_ => Math.Abs(FieldValue("originXMm") - (x0 + 0.1)) < 1e-9, "the job moved 0.1 mm right");
        Assert.Equal(y0, Position().Y);

        // Shift+arrow jogs the stage (up: the simulated stage starts at the far end of its travel); the job stays.
        new Actions(Driver).KeyDown(Keys.Shift).SendKeys(Keys.ArrowUp).KeyUp(Keys.Shift).Perform();
        WaitFor(_ => Position().Y is { } y && y != y0, "the stage jogged");
        Assert.Equal(x0 + 0.1, FieldValue("originXMm"), 9);

        // Esc leaves the job: the arrows then move nothing.
        new Actions(Driver).SendKeys(Keys.Escape).SendKeys(Keys.ArrowRight).Perform();
        WaitFor(_ => Id("stage-host").GetAttribute("data-selected") == "false", "the job left");
        Assert.Equal(x0 + 0.1, FieldValue("originXMm"), 9);
    }

    [Fact]
    public void MachinePanel_1280Wide_PreflightFactFitsOneLineWithTheSentenceAsItsTooltip()
    {
        Size1280x720();
        WaitFor(d => d.FindElement(By.Id("machine-edge-tolerance")).Displayed, "the Machine panel's facts");
        var fact = Id("machine-edge-tolerance");

        // Its text's line boxes, and how far it is cut: one line, whole (the CLI's sentence took five lines there).
        var lines = Convert.ToInt64(Driver.ExecuteScript("const r = document.createRange(); r.selectNodeContents(arguments[0]); return r.getClientRects().length;", fact), CultureInfo.InvariantCulture);
        var cut = Convert.ToInt64(Driver.ExecuteScript("return arguments[0].scrollWidth - arguments[0].clientWidth;", fact), CultureInfo.InvariantCulture);
        Assert.True(lines == 1, $"the Preflight fact takes {lines} lines at 1280 wide: \"{fact.Text}\"");
        Assert.True(cut <= 0, $"the Preflight fact is cut by {cut} px at 1280 wide");
        Assert.StartsWith(fact.Text + ": a switch-on this computer sends later than that", fact.GetAttribute("title"), StringComparison.Ordinal);
        Screenshot("machine-panel-preflight");
    }

    [Fact]
    public void Workspace_NarrowWindowScrolledDown_AbortAndRunStateStayInView()
    {
        OpenSample("text-banner.png");
        foreach (var (width, height) in new[] { (1000, 700), (1099, 700), (1000, 800), (1280, 700) })
        {
            Resize(width, height);
            Driver.ExecuteScript("window.scrollTo(0, document.documentElement.scrollHeight);");
            foreach (var id in new[] { "abort", "status-run" })
            {
                var inView = (bool)Driver.ExecuteScript(
                    """
                    const r = arguments[0].getBoundingClientRect();
                    return r.height > 0 && r.top >= 0 && r.bottom <= window.innerHeight && r.left >= 0 && r.right <= window.innerWidth;
                    """, Id(id))!;
                Assert.True(inView, $"at {width} x {height} scrolled down, #{id} is off-screen");
            }
        }
    }

    [Fact]
    public void Theme_SwitchedDarkAndLight_PageFollowsSettingsKeepItDisabledControlsDimmed()
    {
        OpenSample("qr-code.bmp");
        var main = Host.Services.GetRequiredService<MainViewModel>();
        Assert.Equal("system", main.Settings.Theme);
        string? BodyTheme() => (string?)Driver.ExecuteScript("return document.body.getAttribute('data-theme');");

        // A test move holds the machine: the job's controls and most machine buttons are disabled, the view's are not.
        using (main.Activity.Begin(App.Services.MachineOperation.TestMove("a theme check")))
        {
            WaitFor(d => d.FindElement(By.CssSelector("#samples button.chip")).GetAttribute("disabled") is not null, "the job's controls disabled");
            foreach (var theme in new[] { "dark", "light" })
            {
                Driver.FindElement(By.CssSelector($"#theme option[value='{theme}']")).Click();
                WaitFor(_ => (BodyTheme() == "dark") == (theme == "dark"), theme + " applied");
                WaitFor(_ => main.Settings.Theme == theme, theme + " kept in the settings");
                ColoursSettled();

                // Enabled controls keep their text readable (WCAG 4.5:1); disabled ones are dimmed well below it.
                foreach (var enabled in new[] { "#zoom-fit", "#theme", "#sampleId", ".steps .chip:not(.on)" })
                {
                    Assert.True(Contrast(enabled) >= 4.5, $"{theme}: enabled {enabled} has contrast {Contrast(enabled):0.00}");
                }

                foreach (var disabled in new[] { "#disconnect", "#start", "#samples button.chip", "#widthMm", "#dither", "#aspectLocked" })
                {
                    Assert.True(Id("app").FindElement(By.CssSelector(disabled)).GetAttribute("disabled") is not null, $"{disabled} disabled");
                    Assert.True(Contrast(disabled == "#aspectLocked" ? "label.check:has(#aspectLocked)" : disabled) <= 3, $"{theme}: disabled {disabled} has contrast {Contrast(disabled):0.00}");
                }
            }
        }

        // The settings, not the browser's storage, decide the theme of a window opened again.
        Driver.FindElement(By.CssSelector("#theme option[value='dark']")).Click();
        WaitFor(_ => main.Settings.Theme == "dark", "dark kept in the settings");
        Driver.ExecuteScript("localStorage.clear();");
        Open();
        WaitFor(_ => BodyTheme() == "dark", "dark again after reopening");
        Assert.Equal("dark", Id("theme").GetDomProperty("value"));
        Driver.FindElement(By.CssSelector("#theme option[value='system']")).Click();
        WaitFor(_ => BodyTheme() is null, "the system's (light) mode");
    }

    [Fact]
    public void Workspace_LightAndDark_Screenshots()
    {
        // The page's own area at exactly 1280 x 720, as docs/user-guide.md shows it.
        Driver.ExecuteCdpCommand("Emulation.setDeviceMetricsOverride", new Dictionary<string, object?>
        {
            ["width"] = 1280, ["height"] = 720, ["deviceScaleFactor"] = 1, ["mobile"] = false,
        });
        WaitFor(d => Convert.ToInt64(((IJavaScriptExecutor)d).ExecuteScript("return window.innerHeight;"), CultureInfo.InvariantCulture) == 720, "a 1280 x 720 page");
        OpenSample("qr-code.bmp");
        SetField("widthMm", "12");
        WaitFor(d => d.FindElement(By.Id("status-estimate")).Text.StartsWith("12 × 12 mm", StringComparison.Ordinal), "12 mm job planned");
        Id("connect").Click();
        WaitFor(d => d.FindElement(By.Id("machine-homed")).Displayed && Enabled("jog-x-"), "connected to the simulator, state read");
        WaitFor(d => d.FindElement(By.Id("stage-host")).GetAttribute("data-drawn-moves") != "0", "plan drawn");
        foreach (var theme in new[] { "light", "dark" })
        {
            Driver.FindElement(By.CssSelector($"#theme option[value='{theme}']")).Click();
            WaitFor(d => ((string?)((IJavaScriptExecutor)d).ExecuteScript("return document.body.getAttribute('data-theme');") == "dark") == (theme == "dark"), theme + " applied");
            ColoursSettled();
            // The stage redraws on the theme's change event, at the next frame.
            Driver.ExecuteAsyncScript("requestAnimationFrame(() => requestAnimationFrame(arguments[arguments.length - 1]));");
            var path = Screenshot("workspace-" + theme);
            Assert.True(new FileInfo(path).Length > 20_000);
        }
    }

    [Fact]
    public void Workspace_UserGuideSizes_StageAndPanelsInEveryScreenshot()
    {
        // The user guide's three windows (issue 36): a 1366 x 768 laptop's page at 100 % and at 125 % (1093 x 501 CSS
        // pixels drawn at 1.25), and 1920 x 1080. In each the stage and both panel columns are on screen, side by side.
        foreach (var (name, width, height, scale) in new[] { ("1366x768", 1366, 657, 1.0), ("1366x768-125", 1093, 501, 1.25), ("1920x1080", 1920, 969, 1.0) })
        {
            Driver.ExecuteCdpCommand("Emulation.setDeviceMetricsOverride", new Dictionary<string, object?>
            {
                ["width"] = width, ["height"] = height, ["deviceScaleFactor"] = scale, ["mobile"] = false,
            });
            WaitFor(d => Convert.ToInt64(((IJavaScriptExecutor)d).ExecuteScript("return window.innerHeight;"), CultureInfo.InvariantCulture) == height, $"a {width} x {height} page");
            if (name == "1366x768")
            {
                OpenSample("qr-code.bmp");
                SetField("widthMm", "12");
                Id("connect").Click();
                WaitFor(d => d.FindElement(By.Id("stage-host")).GetAttribute("data-drawn-moves") != "0" && Enabled("jog-x-"), "planned and connected");
            }

            // The panels being edited brought into view in their own columns (each scrolls beside the stage).
            Driver.ExecuteScript("document.getElementById('panel-size').scrollIntoView({ block: 'start' }); document.getElementById('panel-machine').scrollIntoView({ block: 'start' });");
            Driver.ExecuteAsyncScript("requestAnimationFrame(() => requestAnimationFrame(arguments[arguments.length - 1]));");
            foreach (var id in new[] { "stage-canvas", "panel-size", "panel-machine", "start" })
            {
                var inView = (bool)Driver.ExecuteScript(
                    "const r = arguments[0].getBoundingClientRect(); return r.height > 0 && r.top >= 0 && r.left >= 0 && r.right <= window.innerWidth && r.top < window.innerHeight;", Id(id))!;
                Assert.True(inView, $"#{id} is not on screen at {name}");
            }

            Assert.True(new FileInfo(Screenshot("user-guide-" + name)).Length > 20_000);
        }
    }

    [Fact]
    public void FocalSeries_ProfileWithZ_PresetPlannedAndShown()
    {
        Resize(1440, 1000);
        Driver.FindElement(By.CssSelector("#panel-sweep summary")).Click();
        WaitFor(d => d.FindElement(By.Id("sweep-focus-note")).Text.Contains("no Z axis", StringComparison.Ordinal), "focus not offered on two axes");
        var path = Path.Combine(DataFolder, "three-axis.json");
        var profile = Core.Geometry.MachineProfile.Default with { Z = new Core.Geometry.ZAxisProfile() };
        profile.Save(path);

        Host.Services.GetRequiredService<MainViewModel>().UseProfile(path, profile);
        WaitFor(d => d.FindElements(By.Id("sweepFocalSeries")).Count == 1, "the focal series offered");
        Id("sweepFocalSeries").Click();

        WaitFor(d => d.FindElement(By.Id("sweep-summary")).Text.StartsWith("9 × 1 cells", StringComparison.Ordinal), "the focal series planned");
        Driver.ExecuteScript("document.getElementById('panel-sweep').scrollIntoView();");
        Assert.True(new FileInfo(Screenshot("workspace-focal-series")).Length > 20_000);
    }

    [Fact]
    public void DotModeAndSweep_SetInThePanels_PlannedAndShown()
    {
        Resize(1440, 1000);
        OpenSample("qr-code.bmp");
        SetField("widthMm", "5");
        Driver.FindElement(By.CssSelector("#mode option[value='Dots']")).Click();
        WaitFor(d => d.FindElements(By.Id("pulsesPerDot")).Count == 1, "the dot fields shown");
        SetField("pulsesPerDot", "10");
        WaitFor(d => d.FindElement(By.Id("pulses")).Text.Contains("10 pulses per pixel", StringComparison.Ordinal), "10 pulses a pixel");
        Assert.Contains("563 dots", Text("estimate"), StringComparison.Ordinal);

        Driver.FindElement(By.CssSelector("#panel-sweep summary")).Click();
        SetField("sweepRows", "pulses-per-dot=1,5,20");
        SetField("sweepColumns", "pitch=25,50");
        WaitFor(d => d.FindElement(By.Id("sweep-summary")).Text.StartsWith("3 × 2 cells", StringComparison.Ordinal), "the sweep planned");
        Driver.ExecuteScript("document.getElementById('panel-process').scrollIntoView();");
        Assert.True(new FileInfo(Screenshot("workspace-dots")).Length > 20_000);

        // The sweep on the stage instead of the job: its own moves drawn, then the job's again.
        var jobMoves = DrawnMoves();
        Id("sweepShow").Click();
        WaitFor(_ => DrawnMoves() != jobMoves && DrawnMoves() > 0, "the sweep drawn on the stage");
        Driver.ExecuteScript("document.getElementById('panel-sweep').scrollIntoView();");
        Assert.True(new FileInfo(Screenshot("workspace-sweep")).Length > 20_000);
        Id("sweepShow").Click();
        WaitFor(_ => DrawnMoves() == jobMoves, "the job drawn again");

        Driver.FindElement(By.CssSelector("#panel-calibration summary")).Click();
        SetField("calXMeasured", "16.0080");
        SetField("calYMeasured", "15.9920");
        SetField("calAngle", "90.5");
        Id("calSolve").Click();
        WaitFor(d => d.FindElements(By.CssSelector("[data-solution=line]")).Count > 0, "the calibration solved");
        Driver.ExecuteScript("document.getElementById('panel-calibration').scrollIntoView();");
        Assert.True(new FileInfo(Screenshot("workspace-calibration")).Length > 20_000);

        Driver.FindElement(By.CssSelector("#panel-alignment summary")).Click();
        Driver.ExecuteScript("document.getElementById('panel-alignment').scrollIntoView();");
        Assert.True(new FileInfo(Screenshot("workspace-alignment")).Length > 20_000);
        Assert.DoesNotContain(Driver.Manage().Logs.GetLog(LogType.Browser), e => e.Level == LogLevel.Severe);
    }

    [Fact]
    public void Page_Loaded_WeighsLessThan2MB()
    {
        // The first load with an empty cache: the page and everything it loaded, as the browser decoded it.
        var weight = Convert.ToInt64(Driver.ExecuteScript(
            """
            const all = [...performance.getEntriesByType('navigation'), ...performance.getEntriesByType('resource')];
            return all.reduce((n, e) => n + (e.decodedBodySize || 0), 0);
            """), CultureInfo.InvariantCulture);
        var files = Convert.ToInt64(Driver.ExecuteScript("return performance.getEntriesByType('resource').length + 1;"), CultureInfo.InvariantCulture);
        var readyMs = Convert.ToDouble(Driver.ExecuteScript("return performance.getEntriesByName('laserengrave-ready')[0].startTime;"), CultureInfo.InvariantCulture);
        TestContext.Current.TestOutputHelper?.WriteLine($"page weight {weight / 1024} KB in {files} files; usable {readyMs:0} ms after navigation");

        // What weighs what, decoded and as sent (compressed), to see what dominates.
        var parts = Convert.ToString(Driver.ExecuteScript(
            """
            return [...performance.getEntriesByType('navigation'), ...performance.getEntriesByType('resource')]
                .map(e => `${Math.round((e.decodedBodySize || 0) / 1024)} KB (${Math.round((e.transferSize || 0) / 1024)} KB sent) ${e.name.split('?')[0].split('/').slice(-1)[0]}`)
                .join('\n');
            """), CultureInfo.InvariantCulture);
        TestContext.Current.TestOutputHelper?.WriteLine(parts ?? string.Empty);

        Assert.InRange(weight, 50_000, 2_000_000);
    }

    [Fact]
    public void Stage_RulerLabelsWholeAndSweepCellLabelsApart()
    {
        WaitFor(_ => View().Scale > 1, "the stage drawn");
        var canvas = Id("stage-canvas").Size;
        using var rulers = System.Text.Json.JsonDocument.Parse(Id("stage-host").GetAttribute("data-ruler-labels")!);
        var labels = rulers.RootElement.EnumerateArray().Select(l => (Axis: l[0].GetString(), Text: l[1].GetString(), Box: Enumerable.Range(2, 4).Select(i => l[i].GetDouble()).ToArray())).ToList();
        Assert.Contains(labels, l => l.Axis == "y" && l.Text == "60");
        Assert.Contains(labels, l => l.Axis == "x" && l.Text == "60");
        Assert.All(labels, l => Assert.True(l.Box[0] >= 0 && l.Box[1] >= 0 && l.Box[2] <= canvas.Width && l.Box[3] <= canvas.Height, $"{l.Axis} {l.Text} at {string.Join(", ", l.Box)} cut off the {canvas.Width} x {canvas.Height} canvas"));

        // A sweep of 1 mm cells (the default) on the stage: its cells' labels never overlap, at the fitted view or zoomed in.
        OpenSample("qr-code.bmp");
        SetField("widthMm", "5");
        Driver.FindElement(By.CssSelector("#panel-sweep summary")).Click();
        SetField("sweepRows", "speed=0.5,1,2");
        SetField("sweepColumns", "frequency=500,1000,2000");
        WaitFor(d => d.FindElement(By.Id("sweep-summary")).Text.StartsWith("3 × 3 cells", StringComparison.Ordinal), "the sweep planned");
        var jobMoves = DrawnMoves();
        Id("sweepShow").Click();
        WaitFor(_ => DrawnMoves() != jobMoves && DrawnMoves() > 0, "the sweep drawn on the stage");
        // Each label says its values with their units ("0.5 mm/s · 500 Hz"): longer, so all nine fit a few steps further in
        // (at 7 px and more, never overlapping on the way).
        for (var zoom = 0; zoom < 10; zoom++)
        {
            var boxes = BoxLabels();
            for (var i = 0; i < boxes.Length; i++)
            {
                for (var j = i + 1; j < boxes.Length; j++)
                {
                    Assert.False(Overlap(boxes[i], boxes[j]), $"labels {i} and {j} overlap at zoom step {zoom}: {string.Join(",", boxes[i])} and {string.Join(",", boxes[j])}");
                }
            }

            var scale = View().Scale;
            Id("zoom-in").Click();
            WaitFor(_ => View().Scale > scale, "zoomed in");
        }

        Assert.True(BoxLabels().Length >= 9, $"{BoxLabels().Length} labels drawn zoomed in");
        Screenshot("sweep-labels-zoomed");
    }

    [Fact]
    public void Keys_F1EscCtrlOCtrlS_HelpShownAndClosedChooserOpenedBrowserKeysPrevented()
    {
        // Whether the browser's own Ctrl+O/Ctrl+S were prevented (a window listener sees the key after the page's);
        // and the file input's click noted instead of a chooser opening, which headless Chromium cannot show.
        Driver.ExecuteScript("""
            window.__keys = [];
            window.addEventListener('keydown', (e) => window.__keys.push(e.key + (e.defaultPrevented ? ':prevented' : '')));
            document.getElementById('file').addEventListener('click', (e) => { e.preventDefault(); window.__chooser = true; });
            """);
        Driver.FindElement(By.ClassName("brand")).Click();

        new Actions(Driver).SendKeys(Keys.F1).Perform();
        WaitFor(d => d.FindElements(By.Id("help-overlay")).Count == 1, "F1: the help overlay");
        Assert.Contains("Ctrl+O", Text("help-keys"), StringComparison.Ordinal);
        Assert.Contains("Esc", Text("help-keys"), StringComparison.Ordinal);
        Screenshot("help-overlay");
        new Actions(Driver).SendKeys(Keys.Escape).Perform();
        WaitFor(d => d.FindElements(By.Id("help-overlay")).Count == 0, "Esc: the help overlay closed");

        // F1 and Esc act in a field too.
        Id("widthMm").Click();
        new Actions(Driver).SendKeys(Keys.F1).Perform();
        WaitFor(d => d.FindElements(By.Id("help-overlay")).Count == 1, "F1 in a field: the help overlay");
        new Actions(Driver).SendKeys(Keys.Escape).Perform();
        WaitFor(d => d.FindElements(By.Id("help-overlay")).Count == 0, "Esc in a field: the help overlay closed");

        Driver.FindElement(By.ClassName("brand")).Click();
        new Actions(Driver).KeyDown(Keys.Control).SendKeys("o").KeyUp(Keys.Control).Perform();
        WaitFor(d => ((IJavaScriptExecutor)d).ExecuteScript("return window.__chooser === true;") is true, "Ctrl+O: the file chooser");
        new Actions(Driver).KeyDown(Keys.Control).SendKeys("s").KeyUp(Keys.Control).Perform();
        WaitFor(d => d.FindElements(By.Id("layers-file-error")).Count == 1, "Ctrl+S: the layers panel says why nothing was saved");
        var keys = ((IEnumerable<object>)Driver.ExecuteScript("return window.__keys;")!).Select(k => k.ToString()).ToArray();
        Assert.Contains("F1:prevented", keys);
        Assert.Contains("o:prevented", keys);
        Assert.Contains("s:prevented", keys);
    }

    [Fact]
    public void Stage_JobDraggedOffTheTravel_Refused()
    {
        OpenSample("qr-code.bmp");
        SetField("widthMm", "5");
        WaitFor(d => d.FindElement(By.Id("status-estimate")).Text.StartsWith("5 × 5 mm", StringComparison.Ordinal), "5 mm job planned");
        WaitFor(_ => View().Scale > 1, "the stage drawn");
        var (scale, ox, oy) = View();
        var canvas = Id("stage-canvas");

        new Actions(Driver)
            .MoveToLocation((int)(canvas.Location.X + ox + (3 * scale)), (int)(canvas.Location.Y + oy + (3 * scale)))
            .ClickAndHold().MoveByOffset((int)(-5 * scale), 0).Release().Perform();

        WaitFor(d => d.FindElements(By.Id("drop-refused")).Count == 1, "the drop refused");
        Assert.Contains("travel", Text("drop-refused"), StringComparison.Ordinal);
        Assert.Equal(1, FieldValue("originXMm"));
    }
}
