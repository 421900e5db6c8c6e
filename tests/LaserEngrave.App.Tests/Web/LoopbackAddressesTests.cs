using LaserEngrave.App.Web;
using Microsoft.Extensions.Configuration;

namespace LaserEngrave.App.Tests.Web;

public sealed class LoopbackAddressesTests
{
    private static IConfiguration Config(params (string Key, string Value)[] values) =>
        new ConfigurationBuilder().AddInMemoryCollection(values.Select(v => KeyValuePair.Create(v.Key, (string?)v.Value))).Build();

    [Theory]
    [InlineData("http://127.0.0.1:5080")]
    [InlineData("http://127.0.0.1:0")]
    [InlineData("http://localhost:5080")]
    [InlineData("http://[::1]:5080")]
    [InlineData("https://127.0.0.2:5443/")]
    public void IsLoopback_ThisComputer_True(string url) => Assert.True(LoopbackAddresses.IsLoopback(url));

    [Theory]
    [InlineData("http://0.0.0.0:2")]
    [InlineData("http://*:5080")]
    [InlineData("http://+:5080")]
    [InlineData("http://[::]:5080")]
    [InlineData("http://192.168.1.20:5080")]
    [InlineData("http://lab-pc:5080")]
    [InlineData("127.0.0.1:5080")]
    public void IsLoopback_NetworkOrWildcard_False(string url) => Assert.False(LoopbackAddresses.IsLoopback(url));

    [Fact]
    public void Problem_OneOpenAddressAmongLoopback_NamesIt()
    {
        var problem = LoopbackAddresses.Problem(Config(), "http://127.0.0.1:1;http://0.0.0.0:2");

        Assert.StartsWith("http://0.0.0.0:2 (--urls) is not an address of this computer", problem, StringComparison.Ordinal);
        Assert.DoesNotContain('\n', problem!);
    }

    [Fact]
    public void Problem_AppSettingsKestrelEndpointOnTheNetwork_NamesIt()
    {
        var problem = LoopbackAddresses.Problem(Config(("Kestrel:Endpoints:Lab:Url", "http://0.0.0.0:8080")), "http://127.0.0.1:0");

        Assert.StartsWith("http://0.0.0.0:8080 (Kestrel:Endpoints:Lab:Url)", problem, StringComparison.Ordinal);
    }

    [Fact]
    public void Problem_AllLoopback_Null() =>
        Assert.Null(LoopbackAddresses.Problem(Config(("Kestrel:Endpoints:A:Url", "http://localhost:1")), "http://127.0.0.1:0;http://[::1]:0"));
}
