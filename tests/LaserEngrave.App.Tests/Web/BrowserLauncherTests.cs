using LaserEngrave.App.Web;

namespace LaserEngrave.App.Tests.Web;

public sealed class BrowserLauncherTests
{
    [Fact]
    public void FindAppBrowser_FirstThatExists()
    {
        var found = BrowserLauncher.FindAppBrowser(["/a/msedge", "/b/chrome", "/c/chromium"], p => p != "/a/msedge");

        Assert.Equal("/b/chrome", found);
    }

    [Fact]
    public void FindAppBrowser_NoneInstalled_NullSoTheDefaultBrowserOpens()
    {
        Assert.Null(BrowserLauncher.FindAppBrowser(["/a/msedge"], _ => false));
    }

    [Fact]
    public void AppModeArguments_OwnWindowAndProfile()
    {
        var arguments = BrowserLauncher.AppModeArguments("http://127.0.0.1:5080/", "/data/window");

        Assert.Contains("--app=http://127.0.0.1:5080/", arguments);
        Assert.Contains("--user-data-dir=/data/window", arguments);
        Assert.DoesNotContain("--no-sandbox", arguments);
    }

    [Fact]
    public void AppModeArguments_AsRoot_WithoutTheSandboxChromiumRefusesRootFor()
    {
        var arguments = BrowserLauncher.AppModeArguments("http://127.0.0.1:5080/", "/data/window", asRoot: true);

        Assert.Contains("--no-sandbox", arguments);
        Assert.Contains("--app=http://127.0.0.1:5080/", arguments);
    }

    [Theory]
    [InlineData(1280, 800, 40)] // a 13" laptop, the Windows taskbar at the bottom
    [InlineData(1366, 768, 48)] // the commonest laptop screen, the Windows 11 taskbar
    [InlineData(1280, 720, 48)] // 1920 x 1080 at 150 %, the usual scaling of a 15" laptop
    [InlineData(1280, 800, 25)] // a MacBook at its default scaling, the menu bar
    public void AppModeArguments_CommonLaptopScreen_TheWindowFitsBesideTheTaskbar(int screenWidth, int screenHeight, int taskbar)
    {
        var arguments = BrowserLauncher.AppModeArguments("http://127.0.0.1:5080/", "/data/window");

        var size = Assert.Single(arguments, a => a.StartsWith("--window-size=", StringComparison.Ordinal))["--window-size=".Length..].Split(',').Select(v => int.Parse(v, System.Globalization.CultureInfo.InvariantCulture)).ToArray();
        Assert.InRange(size[0], 800, screenWidth);
        Assert.InRange(size[1], 600, screenHeight - taskbar);
    }

    [Fact]
    public void Candidates_ThisSystem_EdgeChromeOrChromium()
    {
        Assert.All(BrowserLauncher.Candidates(), c => Assert.Matches("(?i)edge|chrome|chromium", c));
    }
}
