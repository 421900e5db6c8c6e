using LaserEngrave.App.Web;

namespace LaserEngrave.App.Tests.Web;

public sealed class AppOptionsTests
{
    [Theory]
    [InlineData(new[] { "--no-browser" }, false, null)]
    [InlineData(new[] { "--urls", "http://127.0.0.1:5080" }, true, "http://127.0.0.1:5080")]
    public void Parse_Options_Read(string[] args, bool openBrowser, string? url)
    {
        var options = AppOptions.Parse(args);

        Assert.Equal((openBrowser, url), (options.OpenBrowser, options.Url));
    }

    [Fact]
    public void Parse_IdleExit_SecondsOrTenByDefault()
    {
        Assert.Equal(TimeSpan.FromSeconds(10), AppOptions.Parse([]).IdleExit);
        Assert.Equal(TimeSpan.FromSeconds(2.5), AppOptions.Parse(["--idle-exit", "2.5"]).IdleExit);
        Assert.Throws<ArgumentException>(() => AppOptions.Parse(["--idle-exit", "-1"]));
    }

    [Fact]
    public void Parse_SimulatorOptions_FileNamedOrNone()
    {
        Assert.Null(AppOptions.Parse([]).SimulatorOptionsFile);
        Assert.Equal("twin.json", AppOptions.Parse(["--sim-options", "twin.json"]).SimulatorOptionsFile);
        Assert.Throws<ArgumentException>(() => AppOptions.Parse(["--sim-options"]));
    }

    [Fact]
    public void Parse_HostOption_PassedOn()
    {
        var options = AppOptions.Parse(["--environment=Development", "--no-browser"]);

        Assert.Equal(["--environment=Development"], options.HostArgs);
    }

    [Theory]
    [InlineData("--urls", "http://0.0.0.0:80", "--urls http://0.0.0.0:80: not an address of this computer")]
    [InlineData("--urls", "http://127.0.0.1:1;http://0.0.0.0:2", "--urls http://0.0.0.0:2: not an address")]
    [InlineData("--bogus", null, "unknown option '--bogus'")]
    [InlineData("--urls", null, "--urls needs a value")]
    public void Parse_BadOption_OneLineNamingIt(string option, string? value, string expected)
    {
        string[] args = value is null ? [option] : [option, value];

        var error = Assert.Throws<ArgumentException>(() => AppOptions.Parse(args));

        Assert.Contains(expected, error.Message, StringComparison.Ordinal);
    }
}
