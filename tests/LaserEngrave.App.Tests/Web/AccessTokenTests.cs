using System.Net;
using System.Net.Http.Json;
using LaserEngrave.App.Web;
using Microsoft.AspNetCore.Mvc.Testing;
using Microsoft.Extensions.DependencyInjection;

namespace LaserEngrave.App.Tests.Web;

/// <summary>The start's secret: required by the page and every API call; the old fixed header alone is not enough.</summary>
/// <remarks>
/// The class's tests share one app (<see cref="OneApp"/>, a class fixture): each asks how a request is answered, and
/// none changes what another's answer depends on; an app for each of the 29 cost about half a second of CPU each.
/// </remarks>
public sealed class AccessTokenTests : IClassFixture<AccessTokenTests.OneApp>, IAsyncLifetime
{
    private AppFactory _app = null!;

    private static CancellationToken Token => TestContext.Current.CancellationToken;

    private string Secret => _app.Services.GetRequiredService<AccessToken>().Value;

    public async ValueTask InitializeAsync() =>
        _app = (await TestContext.Current.GetFixture<OneApp>() ?? throw new InvalidOperationException("no app: the class fixture is missing")).App;

    public ValueTask DisposeAsync() => ValueTask.CompletedTask;

    /// <summary>The app the class's tests ask.</summary>
    internal sealed class OneApp : IDisposable
    {
        public AppFactory App { get; } = new();

        public void Dispose() => App.Dispose();
    }

    private HttpClient Client(bool cookies = false) =>
        _app.CreateClient(new WebApplicationFactoryClientOptions { AllowAutoRedirect = false, HandleCookies = cookies });

    [Theory]
    [InlineData("GET", "/api/state")]
    [InlineData("GET", "/api/image/mask.png")]
    [InlineData("GET", "/openapi/v1.json")]
    [InlineData("POST", "/_blazor/negotiate?negotiateVersion=1")]
    [InlineData("GET", "/_blazor?id=x")]
    public async Task ApiAndHub_NoToken_Unauthorized(string method, string path)
    {
        using var client = Client();

        using var response = await client.SendAsync(new HttpRequestMessage(new HttpMethod(method), path), Token);

        Assert.Equal(HttpStatusCode.Unauthorized, response.StatusCode);
        Assert.Contains("token", await response.Content.ReadAsStringAsync(Token), StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("/")]
    [InlineData("/app.css")]
    [InlineData("/boot.js")]
    [InlineData("/_framework/blazor.web.js")]
    public async Task PageShell_NoToken_ServedWithoutStateAndNeverFramed(string path)
    {
        _app.Services.GetRequiredService<App.ViewModels.MainViewModel>().Log.SampleId = "SECRET-SAMPLE";
        using var client = Client();

        using var response = await client.GetAsync(path, Token);

        // A reload cannot carry a header: the shell is served, but it holds no state (not prerendered) until its
        // connection shows the token.
        Assert.Equal(HttpStatusCode.OK, response.StatusCode);
        Assert.DoesNotContain("SECRET-SAMPLE", await response.Content.ReadAsStringAsync(Token), StringComparison.Ordinal);
        Assert.Equal("DENY", response.Headers.GetValues("X-Frame-Options").Single());
        if (path == "/")
        {
            Assert.Equal("frame-ancestors 'none'", response.Headers.GetValues("Content-Security-Policy").Single());
        }

        Assert.DoesNotContain(response.Headers.TryGetValues("Set-Cookie", out var cookies) ? cookies : [], c => c.Contains("LaserEngrave", StringComparison.Ordinal) || c.Contains(Secret, StringComparison.Ordinal));
    }

    [Fact]
    public async Task Post_OnlyTheOldFixedHeader_UnauthorizedAndNothingStarts()
    {
        using var client = Client();
        client.DefaultRequestHeaders.Add("X-LaserEngrave", "1");

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

    [Theory]
    [InlineData(true)]
    [InlineData(false)]
    public async Task Page_TokenInAddress_UnauthorizedEvenTheRightOneAndNoCookie(bool right)
    {
        using var client = Client(cookies: true);

        // An address is kept by the browser's history: the token is never taken from one, right or wrong.
        using var response = await client.GetAsync($"/?token={(right ? Secret : "guess")}", Token);

        Assert.Equal(HttpStatusCode.Unauthorized, response.StatusCode);
        Assert.False(response.Headers.Contains("Set-Cookie"));
    }

    [Theory]
    [InlineData("/")]
    [InlineData("/?x=1")]
    public async Task Page_Served_NoCookieForOtherPortsToReceive(string path)
    {
        using var client = Client(cookies: true);

        using var response = await client.GetAsync(path, Token);

        // A cookie cannot be kept to one port: whatever the app set, every server on 127.0.0.1 would receive.
        Assert.Equal(HttpStatusCode.OK, response.StatusCode);
        Assert.False(response.Headers.Contains("Set-Cookie"), string.Join("; ", response.Headers.TryGetValues("Set-Cookie", out var set) ? set : []));
    }

    private async Task<HttpResponseMessage> TradeAsync(string? code, string? origin = null)
    {
        using var client = Client();
        using var request = new HttpRequestMessage(HttpMethod.Post, "/api/session");
        if (code is not null)
        {
            request.Headers.Add(LaunchCodes.HeaderName, code);
        }

        if (origin is not null)
        {
            request.Headers.Add("Origin", origin);
        }

        return await client.SendAsync(request, Token);
    }

    [Fact]
    public async Task Session_LaunchCode_TokenOnceThenUnauthorized()
    {
        var code = _app.Services.GetRequiredService<LaunchCodes>().Issue();

        using var first = await TradeAsync(code, origin: "http://localhost");
        using var again = await TradeAsync(code);

        Assert.Equal(HttpStatusCode.OK, first.StatusCode);
        Assert.Equal(Secret, (await first.Content.ReadFromJsonAsync<System.Text.Json.JsonElement>(Token)).GetProperty("token").GetString());
        Assert.Contains("no-store", first.Headers.CacheControl?.ToString() ?? string.Empty, StringComparison.Ordinal);
        Assert.False(first.Headers.Contains("Set-Cookie"));
        Assert.Equal(HttpStatusCode.Unauthorized, again.StatusCode);
        Assert.DoesNotContain(Secret, await again.Content.ReadAsStringAsync(Token), StringComparison.Ordinal);
    }

    [Theory]
    [InlineData(null)]
    [InlineData("")]
    [InlineData("guess")]
    public async Task Session_NoOrUnknownLaunchCode_Unauthorized(string? code)
    {
        using var response = await TradeAsync(code);

        Assert.Equal(HttpStatusCode.Unauthorized, response.StatusCode);
        Assert.DoesNotContain(Secret, await response.Content.ReadAsStringAsync(Token), StringComparison.Ordinal);
    }

    [Fact]
    public async Task Session_AnotherPagesOrigin_ForbiddenAndTheCodeKept()
    {
        var code = _app.Services.GetRequiredService<LaunchCodes>().Issue();

        using var foreign = await TradeAsync(code, origin: "http://127.0.0.1:1");
        using var own = await TradeAsync(code);

        Assert.Equal(HttpStatusCode.Forbidden, foreign.StatusCode);
        Assert.Equal(HttpStatusCode.OK, own.StatusCode);
    }

    [Fact]
    public async Task Proof_Challenge_HmacOfTheTokenAndTheProcessId()
    {
        using var client = Client();
        const string challenge = "0123456789abcdef-_XYZ";

        var answer = await client.GetFromJsonAsync<System.Text.Json.JsonElement>($"/api/proof?challenge={challenge}", Token);

        var expected = Convert.ToHexStringLower(System.Security.Cryptography.HMACSHA256.HashData(
            System.Text.Encoding.ASCII.GetBytes(Secret), System.Text.Encoding.ASCII.GetBytes("laserengrave-proof:" + challenge)));
        Assert.Equal(expected, answer.GetProperty("proof").GetString());
        Assert.Equal(Environment.ProcessId, answer.GetProperty("pid").GetInt32());
        Assert.Equal("LaserEngrave", answer.GetProperty("app").GetString());
    }

    [Theory]
    [InlineData("")]
    [InlineData("short")]
    [InlineData("0123456789abcdef%20")]
    public async Task Proof_ChallengeNotANonce_BadRequest(string challenge)
    {
        using var client = Client();

        using var response = await client.GetAsync($"/api/proof?challenge={challenge}", Token);

        Assert.Equal(HttpStatusCode.BadRequest, response.StatusCode);
    }

    [Fact]
    public async Task Requests_OnlyThePagesCookies_Unauthorized()
    {
        // What a browser sends by itself after the page was opened: its cookies, here the old design's token cookie too.
        using var client = Client();
        var port = _app.Server.BaseAddress.Port;
        client.DefaultRequestHeaders.Add("Cookie", $"LaserEngrave-Token-{port}={Secret}; LaserEngrave-Token-80={Secret}");

        using var state = await client.GetAsync("/api/state", Token);
        using var fire = await client.PostAsync("/api/moves/fire", JsonContent.Create(new { pulses = 10 }), Token);
        using var negotiate = await client.PostAsync("/_blazor/negotiate?negotiateVersion=1", null, Token);

        Assert.Equal(HttpStatusCode.Unauthorized, state.StatusCode);
        Assert.Equal(HttpStatusCode.Unauthorized, fire.StatusCode);
        Assert.Equal(HttpStatusCode.Unauthorized, negotiate.StatusCode);
    }

    [Theory]
    [InlineData("Authorization")]
    [InlineData("access_token")]
    public async Task BlazorHub_TokenShown_Negotiated(string how)
    {
        using var client = Client();
        var path = "/_blazor/negotiate?negotiateVersion=1";
        if (how == "Authorization")
        {
            client.DefaultRequestHeaders.Authorization = new("Bearer", Secret);
        }
        else
        {
            path += $"&access_token={Secret}";
        }

        using var negotiate = await client.PostAsync(path, null, Token);

        Assert.Equal(HttpStatusCode.OK, negotiate.StatusCode);
        Assert.Contains("connectionToken", await negotiate.Content.ReadAsStringAsync(Token), StringComparison.Ordinal);
    }

    [Fact]
    public async Task Api_TokenInQuery_NotTakenOutsideTheHub()
    {
        using var client = Client();

        using var response = await client.GetAsync($"/api/state?access_token={Secret}", Token);

        Assert.Equal(HttpStatusCode.Unauthorized, response.StatusCode);
    }

    [Theory]
    [InlineData("POST", "/api/moves/fire", "http://evil.example")]
    [InlineData("POST", "/api/settings/theme", "http://127.0.0.1:1")]
    [InlineData("POST", "/api/run/start", "null")]
    [InlineData("POST", "/_blazor/negotiate?negotiateVersion=1", "http://evil.example")]
    [InlineData("POST", "/_blazor/negotiate?negotiateVersion=1", "http://localhost:1")]
    [InlineData("GET", "/_blazor?id=x", "http://127.0.0.1:1")]
    [InlineData("POST", "/_blazor/disconnect", "http://127.0.0.1:1")]
    [InlineData("GET", "/api/state", "https://localhost")]
    public async Task ForeignOrigin_EvenWithTheToken_Forbidden(string method, string path, string origin)
    {
        using var client = Client();
        client.DefaultRequestHeaders.Authorization = new("Bearer", Secret);
        using var request = new HttpRequestMessage(new HttpMethod(method), path) { Content = JsonContent.Create(new { pulses = 10, theme = "dark" }) };
        request.Headers.Add("Origin", origin);

        using var response = await client.SendAsync(request, Token);

        Assert.Equal(HttpStatusCode.Forbidden, response.StatusCode);
        Assert.Contains("another page", await response.Content.ReadAsStringAsync(Token), StringComparison.Ordinal);
    }

    [Fact]
    public async Task OwnOrigin_WithTheToken_Allowed()
    {
        using var client = Client();
        client.DefaultRequestHeaders.Authorization = new("Bearer", Secret);
        var own = _app.Server.BaseAddress.GetLeftPart(UriPartial.Authority);
        using var request = new HttpRequestMessage(HttpMethod.Post, "/api/settings/theme") { Content = JsonContent.Create(new { theme = "dark" }) };
        request.Headers.Add("Origin", own);
        using var negotiate = new HttpRequestMessage(HttpMethod.Post, "/_blazor/negotiate?negotiateVersion=1");
        negotiate.Headers.Add("Origin", own);

        using var response = await client.SendAsync(request, Token);
        using var hub = await client.SendAsync(negotiate, Token);

        Assert.Equal(HttpStatusCode.OK, response.StatusCode);
        Assert.Equal(HttpStatusCode.OK, hub.StatusCode);
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
