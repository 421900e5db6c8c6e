using System.Net;
using System.Net.Http.Json;
using LaserEngrave.App.Web;
using Microsoft.AspNetCore.Mvc.Testing;
using Microsoft.Extensions.DependencyInjection;

namespace LaserEngrave.App.Tests.Web;

/// <summary>The start's secret: required by the page and every API call; the old fixed header alone is not enough.</summary>
public sealed class AccessTokenTests : IDisposable
{
    private readonly AppFactory _app = new();

    private static CancellationToken Token => TestContext.Current.CancellationToken;

    private string Secret => _app.Services.GetRequiredService<AccessToken>().Value;

    public void Dispose() => _app.Dispose();

    private HttpClient Client(bool cookies = false) =>
        _app.CreateClient(new WebApplicationFactoryClientOptions { AllowAutoRedirect = false, HandleCookies = cookies });

    [Theory]
    [InlineData("/")]
    [InlineData("/app.css")]
    [InlineData("/_framework/blazor.web.js")]
    [InlineData("/api/state")]
    public async Task Get_NoToken_Unauthorized(string path)
    {
        using var client = Client();

        using var response = await client.GetAsync(path, Token);

        Assert.Equal(HttpStatusCode.Unauthorized, response.StatusCode);
        Assert.Contains("token", await response.Content.ReadAsStringAsync(Token), StringComparison.Ordinal);
    }

    [Fact]
    public async Task Post_OnlyTheOldFixedHeader_UnauthorizedAndNothingStarts()
    {
        using var client = Client();
        client.DefaultRequestHeaders.Add(AppHost.RequestHeader, "1");

        using var response = await client.PostAsync("/api/moves/fire", JsonContent.Create(new { pulses = 10 }), Token);

        Assert.Equal(HttpStatusCode.Unauthorized, response.StatusCode);
    }

    [Fact]
    public async Task Api_WrongToken_Unauthorized()
    {
        using var client = Client();
        client.DefaultRequestHeaders.Authorization = new("Bearer", Secret[..^1] + (Secret[^1] == 'A' ? "B" : "A"));

        using var response = await client.GetAsync("/api/state", Token);

        Assert.Equal(HttpStatusCode.Unauthorized, response.StatusCode);
    }

    [Theory]
    [InlineData("Authorization")]
    [InlineData(AccessToken.HeaderName)]
    public async Task Api_TokenInHeader_AllowedWithoutTheOldHeader(string header)
    {
        using var client = Client();
        client.DefaultRequestHeaders.TryAddWithoutValidation(header, header == "Authorization" ? $"Bearer {Secret}" : Secret);

        using var state = await client.GetAsync("/api/state", Token);
        using var post = await client.PostAsync("/api/settings/theme", JsonContent.Create(new { theme = "dark" }), Token);

        Assert.Equal(HttpStatusCode.OK, state.StatusCode);
        Assert.Equal(HttpStatusCode.OK, post.StatusCode);
    }

    [Fact]
    public async Task Page_TokenInAddress_StrictHttpOnlyCookieThenRedirectWithoutIt()
    {
        using var client = Client(cookies: true);

        using var first = await client.GetAsync($"/?token={Secret}", Token);

        Assert.Equal(HttpStatusCode.Redirect, first.StatusCode);
        Assert.Equal("/", first.Headers.Location!.OriginalString);
        var cookie = Assert.Single(first.Headers.GetValues("Set-Cookie"));
        Assert.Contains("httponly", cookie, StringComparison.OrdinalIgnoreCase);
        Assert.Contains("samesite=strict", cookie, StringComparison.OrdinalIgnoreCase);
        using var page = await client.GetAsync("/", Token);
        Assert.Equal(HttpStatusCode.OK, page.StatusCode);
        using var state = await client.GetAsync("/api/state", Token);
        Assert.Equal(HttpStatusCode.OK, state.StatusCode);
    }

    [Fact]
    public async Task Post_ByCookieWithoutTheAppHeader_Forbidden()
    {
        using var client = Client(cookies: true);
        using var first = await client.GetAsync($"/?token={Secret}", Token);

        using var bare = await client.PostAsync("/api/settings/theme", JsonContent.Create(new { theme = "dark" }), Token);
        client.DefaultRequestHeaders.Add(AppHost.RequestHeader, "1");
        using var withHeader = await client.PostAsync("/api/settings/theme", JsonContent.Create(new { theme = "dark" }), Token);

        Assert.Equal(HttpStatusCode.Forbidden, bare.StatusCode);
        Assert.Equal(HttpStatusCode.OK, withHeader.StatusCode);
    }

    [Fact]
    public async Task BlazorHub_NoCookie_UnauthorizedEvenWithTheAppHeader()
    {
        using var client = Client();
        client.DefaultRequestHeaders.Add(AppHost.RequestHeader, "1");

        using var negotiate = await client.PostAsync("/_blazor/negotiate?negotiateVersion=1", null, Token);

        Assert.Equal(HttpStatusCode.Unauthorized, negotiate.StatusCode);
    }

    [Fact]
    public async Task BlazorHub_ByCookie_AllowedWithoutTheAppHeader()
    {
        using var client = Client(cookies: true);
        using var first = await client.GetAsync($"/?token={Secret}", Token);

        // Blazor's own connection cannot add the app's header; the page's cookie is what lets it in.
        using var negotiate = await client.PostAsync("/_blazor/negotiate?negotiateVersion=1", null, Token);

        Assert.Equal(HttpStatusCode.OK, negotiate.StatusCode);
        Assert.Contains("connectionToken", await negotiate.Content.ReadAsStringAsync(Token), StringComparison.Ordinal);
    }

    [Fact]
    public async Task Page_WrongTokenInAddress_UnauthorizedAndNoCookie()
    {
        using var client = Client();

        using var response = await client.GetAsync("/?token=guess", Token);

        Assert.Equal(HttpStatusCode.Unauthorized, response.StatusCode);
        Assert.False(response.Headers.Contains("Set-Cookie"));
    }

    [Fact]
    public void New_EachStart_DifferentAnd256Bits()
    {
        var a = new AccessToken().Value;
        var b = new AccessToken().Value;

        Assert.NotEqual(a, b);
        Assert.Equal(43, a.Length);
    }
}
