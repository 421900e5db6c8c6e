using System.Net;
using System.Net.Http.Json;
using System.Text.Json;
using LaserEngrave.App.Services;
using LaserEngrave.App.Tests.ViewModels;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Devices.Execution;
using Microsoft.Extensions.DependencyInjection;
using NSubstitute;

namespace LaserEngrave.App.Tests.Web;

/// <summary>The API while a run holds the machine: every other machine command and every job change is a 409 naming the run.</summary>
public sealed class ApiInterlockTests : IDisposable
{
    private readonly IRunService _runs = Substitute.For<IRunService>();
    private readonly TaskCompletionSource _started = new(TaskCreationOptions.RunContinuationsAsynchronously);
    private readonly List<CancellationToken> _tokens = [];
    private readonly AppFactory _app;
    private readonly HttpClient _client;

    public ApiInterlockTests()
    {
        _runs.RunAsync(Arg.Any<EngraveSession>(), Arg.Any<IProgress<EngraveProgress>>(), Arg.Any<CancellationToken>())
            .Returns(async c =>
            {
                var token = c.Arg<CancellationToken>();
                lock (_tokens)
                {
                    _tokens.Add(token);
                }

                c.Arg<IProgress<EngraveProgress>>().Report(SessionResults.Report(RunState.Running, 1, 10, 0, 5));
                _started.TrySetResult();
                await Task.Delay(Timeout.Infinite, token).ContinueWith(_ => { }, TaskScheduler.Default);

                // As the session ends an aborted run: with a result, never by throwing.
                return SessionResults.Ended(c.Arg<EngraveSession>(), SessionResults.Result(RunOutcome.Aborted, "aborted by the operator"));
            });
        _app = new AppFactory(services => services.AddSingleton(_runs));
        _client = _app.NewClient();
    }

    private static CancellationToken Token => TestContext.Current.CancellationToken;

    public void Dispose()
    {
        _client.Dispose();
        _app.Dispose();
    }

    private async Task<(HttpStatusCode Status, JsonElement Body)> PostAsync(string path, object body)
    {
        using var response = await _client.PostAsJsonAsync(path, body, Token);
        return (response.StatusCode, await response.Content.ReadFromJsonAsync<JsonElement>(Token));
    }

    private async Task<JsonElement> WaitForAsync(Func<JsonElement, bool> condition)
    {
        // The state polled until the machine's own completion shows; the bound only stops a broken test from hanging.
        var state = default(JsonElement);
        for (var i = 0; i < 3000; i++)
        {
            state = await _client.GetFromJsonAsync<JsonElement>("/api/state", Token);
            if (condition(state))
            {
                return state;
            }

            await Task.Delay(10, Token);
        }

        throw new TimeoutException($"the state never reached the condition; machine: {state.GetProperty("machine")}, activity: {state.GetProperty("activity")}");
    }

    private async Task StartHeldRunAsync()
    {
        using var folder = TestFiles.NewFolder();
        using (var content = new ByteArrayContent(await File.ReadAllBytesAsync(TestFiles.WriteChecker(folder.Path, 8, 6), Token)))
        using (var upload = await _client.PostAsync("/api/image?name=checker.png", content, Token))
        {
            Assert.Equal(HttpStatusCode.OK, upload.StatusCode);
        }

        Assert.Equal(HttpStatusCode.OK, (await PostAsync("/api/job", new { widthMm = 0.8, originXMm = 0, originYMm = 0 })).Status);
        Assert.Equal(HttpStatusCode.Accepted, (await PostAsync("/api/machine/connect", new { useSimulator = true })).Status);
        await WaitForAsync(s => s.GetProperty("machine").GetProperty("connected").GetBoolean() && !s.GetProperty("activity").GetProperty("busy").GetBoolean());
        Assert.Equal(HttpStatusCode.Accepted, (await PostAsync("/api/run/start", new { })).Status);
        await _started.Task.WaitAsync(TimeSpan.FromSeconds(30), Token);
    }

    [Theory]
    [InlineData("/api/machine/home", "{}")]
    [InlineData("/api/machine/identify", "{}")]
    [InlineData("/api/machine/connect", """{"useSimulator":true}""")]
    [InlineData("/api/machine/disconnect", "{}")]
    [InlineData("/api/moves/jog", """{"direction":"x+","stepUm":1000}""")]
    [InlineData("/api/moves/goto", """{"xMm":1,"yMm":1}""")]
    [InlineData("/api/moves/origin", "{}")]
    [InlineData("/api/moves/frame", "{}")]
    [InlineData("/api/moves/fire", """{"pulses":10}""")]
    [InlineData("/api/job", """{"widthMm":2}""")]
    [InlineData("/api/job", """{"originXMm":3}""")]
    [InlineData("/api/job", """{"thresholdPercent":20}""")]
    [InlineData("/api/job", """{"burnSpeedMmPerS":2}""")]
    [InlineData("/api/image/open", """{"path":"/tmp/other.png"}""")]
    [InlineData("/api/logs/load", """{"path":"/tmp/run.json"}""")]
    public async Task Command_WhileRunning_ConflictNamingTheRun(string path, string json)
    {
        await StartHeldRunAsync();
        var before = await _client.GetFromJsonAsync<JsonElement>("/api/state", Token);

        using var content = new StringContent(json, System.Text.Encoding.UTF8, "application/json");
        using var response = await _client.PostAsync(path, content, Token);

        Assert.Equal(HttpStatusCode.Conflict, response.StatusCode);
        var body = await response.Content.ReadFromJsonAsync<JsonElement>(Token);
        Assert.StartsWith("a run is under way", body.GetProperty("error").GetString(), StringComparison.Ordinal);
        var after = await _client.GetFromJsonAsync<JsonElement>("/api/state", Token);
        Assert.Equal(before.GetProperty("job").GetRawText(), after.GetProperty("job").GetRawText());
        Assert.True(after.GetProperty("machine").GetProperty("connected").GetBoolean());
        Assert.Equal("Running", after.GetProperty("run").GetProperty("state").GetString());
    }

    [Fact]
    public async Task Upload_WhileRunning_ConflictAndNothingSaved()
    {
        await StartHeldRunAsync();
        var images = Directory.GetFiles(Path.Combine(_app.DataFolder, "images"), "*", SearchOption.AllDirectories);

        using var content = new ByteArrayContent(await File.ReadAllBytesAsync(TestFiles.Asset("qr-code.bmp"), Token));
        using var response = await _client.PostAsync("/api/image?name=qr-code.bmp", content, Token);

        Assert.Equal(HttpStatusCode.Conflict, response.StatusCode);
        Assert.Equal(images, Directory.GetFiles(Path.Combine(_app.DataFolder, "images"), "*", SearchOption.AllDirectories));
    }

    [Fact]
    public async Task Start_SecondWhileRunning_IgnoredWithNoteNeverAnAbort()
    {
        await StartHeldRunAsync();

        var (status, body) = await PostAsync("/api/run/start", new { });

        Assert.Equal(HttpStatusCode.OK, status);
        Assert.Contains("ignored", body.GetProperty("note").GetString(), StringComparison.Ordinal);
        Assert.Equal("Running", body.GetProperty("state").GetProperty("run").GetProperty("state").GetString());
        lock (_tokens)
        {
            Assert.False(Assert.Single(_tokens).IsCancellationRequested);
        }
    }

    [Fact]
    public async Task Abort_WhileRunning_AllowedAndMachineFreeAfter()
    {
        await StartHeldRunAsync();

        var (status, _) = await PostAsync("/api/run/abort", new { });
        var state = await WaitForAsync(s => !s.GetProperty("activity").GetProperty("busy").GetBoolean());

        Assert.Equal(HttpStatusCode.OK, status);
        Assert.Equal("Aborted", state.GetProperty("run").GetProperty("state").GetString());
        Assert.Equal(HttpStatusCode.Accepted, (await PostAsync("/api/machine/identify", new { })).Status);
    }
}
