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

    [Fact]
    public void Candidates_ThisSystem_EdgeChromeOrChromium()
    {
        Assert.All(BrowserLauncher.Candidates(), c => Assert.Matches("(?i)edge|chrome|chromium", c));
    }
}
