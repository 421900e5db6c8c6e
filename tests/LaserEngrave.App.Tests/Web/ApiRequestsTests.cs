using System.Net;
using System.Net.Http.Json;
using System.Text;
using System.Text.Json;
using LaserEngrave.App.ViewModels;
using LaserEngrave.App.Web;
using Microsoft.Extensions.DependencyInjection;

namespace LaserEngrave.App.Tests.Web;

/// <summary>Malformed requests are refused in a line before they move the stage or reach the state (issue 32, finding 4).</summary>
public sealed class ApiRequestsTests : IDisposable
{
    private readonly AppFactory _app = new();
    private readonly HttpClient _client;

    public ApiRequestsTests()
    {
        _client = _app.NewClient();
    }

    private static CancellationToken Token => TestContext.Current.CancellationToken;

    public void Dispose()
    {
        _client.Dispose();
        _app.Dispose();
    }

    private async Task<(HttpStatusCode Status, JsonElement Body)> SendAsync(string path, string json)
    {
        using var content = new StringContent(json, Encoding.UTF8, "application/json");
        using var response = await _client.PostAsync(path, content, Token);
        var text = await response.Content.ReadAsStringAsync(Token);
        return (response.StatusCode, text.Length == 0 ? default : JsonDocument.Parse(text).RootElement.Clone());
    }

    private async Task<JsonElement> StateAsync()
    {
        using var response = await _client.GetAsync("/api/state", Token);
        Assert.Equal(HttpStatusCode.OK, response.StatusCode);
        return await response.Content.ReadFromJsonAsync<JsonElement>(Token);
    }

    private static string Error(JsonElement body) => body.GetProperty("error").GetString()!;

    [Theory]
    [InlineData("{}", "xMm")]
    [InlineData("{\"xMm\": 10}", "yMm")]
    [InlineData("{\"yMm\": 10}", "xMm")]
    public async Task GoTo_MissingCoordinate_RefusedAndNothingSet(string json, string missing)
    {
        var (status, body) = await SendAsync("/api/moves/goto", json);

        Assert.Equal(HttpStatusCode.BadRequest, status);
        Assert.Contains(missing, Error(body), StringComparison.Ordinal);
        var moves = (await StateAsync()).GetProperty("testMoves");
        Assert.Equal(JsonValueKind.Null, moves.GetProperty("error").ValueKind);
        Assert.Equal(0, moves.GetProperty("goToXMm").GetDouble());
    }

    [Theory]
    [InlineData("/api/moves/goto", "{\"xMm\": \"NaN\", \"yMm\": 1}", "xMm has a value of the wrong type")]
    [InlineData("/api/moves/goto", "{\"xMm\": 1, \"yMm\": 1e309}", "yMm must be a finite number")]
    [InlineData("/api/moves/jog", "{\"direction\": \"x+\", \"stepUm\": \"NaN\"}", "stepUm has a value of the wrong type")]
    [InlineData("/api/moves/jog", "{\"direction\": \"x+\", \"stepUm\": \"Infinity\"}", "stepUm has a value of the wrong type")]
    [InlineData("/api/moves/jog", "{\"direction\": \"x+\", \"stepUm\": -1e400}", "stepUm must be a finite number")]
    [InlineData("/api/moves/goto", "{\"xMm\": \"5\", \"yMm\": 1}", "xMm has a value of the wrong type")]
    [InlineData("/api/moves/jog", "{\"direction\": \"up\"}", "direction 'up' is not one of x+, x-, y+, y-")]
    [InlineData("/api/moves/jog", "{\"stepUm\": 5}", "direction")]
    [InlineData("/api/moves/jog", "{\"direction\": null}", "direction must not be null")]
    [InlineData("/api/moves/goto", "{\"xMm\": 1, \"yMm\": 1, \"zMm\": 1}", "'zMm' is not a field of this request")]
    [InlineData("/api/moves/fire", "{\"pulses\": \"5\"}", "pulses has a value of the wrong type")]
    [InlineData("/api/image/open", "\"\"", "the request body must be a JSON object")]
    [InlineData("/api/image/open", "{\"path\": \"\"}", "path is empty")]
    [InlineData("/api/image/open", "{}", "path")]
    [InlineData("/api/moves/goto", "{\"xMm\": 1,", "not valid JSON")]
    public async Task Body_Unusable_RefusedInOneLineAndTheStateStillAnswers(string route, string json, string error)
    {
        var (status, body) = await SendAsync(route, json);

        Assert.Equal(HttpStatusCode.BadRequest, status);
        Assert.Contains(error, Error(body), StringComparison.Ordinal);
        Assert.DoesNotContain('\n', Error(body));
        var state = await StateAsync();
        Assert.Equal(100, state.GetProperty("testMoves").GetProperty("stepUm").GetDouble());
    }

    [Theory]
    [InlineData("{\"widthMm\": 1e309}", "widthMm", "1e309 is not a finite number")]
    [InlineData("{\"originXMm\": \"NaN\"}", "originXMm", "'NaN' is not a number")]
    [InlineData("{\"laserFrequencyHz\": \"1,000\"}", "laserFrequencyHz", "'1,000' is not a number")]
    [InlineData("{\"dither\": \"99\"}", "dither", "'99' is not one of")]
    [InlineData("{\"dither\": \"None, Bayer\"}", "dither", "is not one of")]
    [InlineData("{\"strategy\": 3}", "strategy", "is not one of")]
    [InlineData("{\"passes\": -1}", "passes", "-1 is not a whole number")]
    public async Task Job_NonFiniteOrUndefinedValue_RefusedNeverKeptAndStateAnswers(string json, string field, string error)
    {
        var before = (await StateAsync()).GetProperty("job");

        var (status, body) = await SendAsync("/api/job", json);

        Assert.Equal(HttpStatusCode.BadRequest, status);
        Assert.Contains(error, body.GetProperty("errors").GetProperty(field).GetString(), StringComparison.Ordinal);
        var after = (await StateAsync()).GetProperty("job");
        Assert.Equal(before.GetProperty("dither").GetString(), after.GetProperty("dither").GetString());
        Assert.Equal(before.GetProperty("widthMm").GetDouble(), after.GetProperty("widthMm").GetDouble());
        Assert.Equal(before.GetProperty("originXMm").GetDouble(), after.GetProperty("originXMm").GetDouble());
        var settings = Path.Combine(_app.DataFolder, "settings.json");
        Assert.False(File.Exists(settings) && File.ReadAllText(settings).Contains("99", StringComparison.Ordinal));
    }

    [Fact]
    public async Task Job_UnknownFieldOfManyCharacters_QuotedShort()
    {
        var name = new string('q', 5000);

        var (status, body) = await SendAsync("/api/job", $"{{\"{name}\": 1}}");

        Assert.Equal(HttpStatusCode.BadRequest, status);
        var error = Assert.Single(body.GetProperty("errors").EnumerateObject()).Value.GetString()!;
        Assert.True(error.Length < 200, error);
        Assert.Contains("5000 characters", error, StringComparison.Ordinal);
    }

    [Fact]
    public async Task Jog_LongDirection_RefusedQuotingAShortPrefixAndNeverInTheState()
    {
        var direction = new string('x', 50_000);

        var (status, body) = await SendAsync("/api/moves/jog", JsonSerializer.Serialize(new { direction }));

        Assert.Equal(HttpStatusCode.BadRequest, status);
        Assert.True(Error(body).Length < 200, Error(body));
        Assert.DoesNotContain(new string('x', 100), (await StateAsync()).ToString(), StringComparison.Ordinal);
    }

    [Theory]
    [InlineData(true)]
    [InlineData(false)]
    public async Task Body_LargerThan64KB_Refused413WhetherItsLengthIsSaidOrNot(bool saysLength)
    {
        var json = "{\"direction\": \"x+\", " + string.Concat(Enumerable.Range(0, 20_000).Select(i => $"\"f{i}\": 1, ")) + "\"stepUm\": 5}";
        using var content = saysLength
            ? new StringContent(json, Encoding.UTF8, "application/json")
            : (HttpContent)new StreamContent(new UnknownLengthStream(Encoding.UTF8.GetBytes(json)));
        content.Headers.ContentType = new("application/json");

        using var response = await _client.PostAsync("/api/moves/jog", content, Token);

        Assert.Equal(HttpStatusCode.RequestEntityTooLarge, response.StatusCode);
        var error = (await response.Content.ReadFromJsonAsync<JsonElement>(Token)).GetProperty("error").GetString();
        Assert.Contains("more than the 64 KB a JSON request may have", error, StringComparison.Ordinal);
    }

    [Fact]
    public async Task State_NonFiniteValueInAViewModel_StillAnswered()
    {
        var main = _app.Services.GetRequiredService<MainViewModel>();
        main.TestMoves.GoToXMm = double.NaN;
        main.Job.OriginYMm = double.PositiveInfinity;

        var state = await StateAsync();

        Assert.Equal("NaN", state.GetProperty("testMoves").GetProperty("goToXMm").GetString());
    }

    [Fact]
    public async Task Export_WithoutItsPath_400NamingIt()
    {
        using var response = await _client.GetAsync("/api/logs/export", Token);

        Assert.Equal(HttpStatusCode.BadRequest, response.StatusCode);
        Assert.Equal("the request lacks path (docs/api.md)", (await response.Content.ReadFromJsonAsync<JsonElement>(Token)).GetProperty("error").GetString());
    }

    [Fact]
    public void Quote_LongOrControlText_ShortPrefixWithoutControls()
    {
        Assert.Equal("a?b", ApiRequests.Quote("a\nb"));
        Assert.Equal(new string('z', ApiRequests.QuoteLength) + "… (1000 characters)", ApiRequests.Quote(new string('z', 1000)));
    }

    /// <summary>A body sent chunked, without Content-Length.</summary>
    private sealed class UnknownLengthStream(byte[] bytes) : MemoryStream(bytes)
    {
        public override bool CanSeek => false;
    }
}
