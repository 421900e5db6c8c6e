using System.Net;
using System.Net.Http.Json;
using System.Text.Json;
using LaserEngrave.App.ViewModels;
using LaserEngrave.App.Web;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Logging;
using Microsoft.Extensions.DependencyInjection;

namespace LaserEngrave.App.Tests.Web;

public sealed class ApiEndpointsTests : IDisposable
{
    private readonly AppFactory _app = new();
    private readonly HttpClient _client;

    public ApiEndpointsTests()
    {
        _client = _app.NewClient();
    }

    private static CancellationToken Token => TestContext.Current.CancellationToken;

    public void Dispose()
    {
        _client.Dispose();
        _app.Dispose();
    }

    private async Task<JsonElement> StateAsync() => await _client.GetFromJsonAsync<JsonElement>("/api/state", Token);

    [Fact]
    public async Task State_RunUnderWay_XAndYAreWhereTheEngineTimingPutsTheStageNotItsLastReport()
    {
        // Issue 36 finding 1: run.x stayed at the row's start for the whole row (the engine reports once a row).
        var main = _app.Services.GetRequiredService<MainViewModel>();
        main.Run.Bar.ShowLaser(new PacedLaser(12_345, 6_789, 2.5));

        var run = (await StateAsync()).GetProperty("run");

        Assert.Equal(12_345, run.GetProperty("x").GetInt64());
        Assert.Equal(6_789, run.GetProperty("y").GetInt64());
        Assert.Equal(2.5, run.GetProperty("atSeconds").GetDouble());
        Assert.Equal(JsonValueKind.Null, run.GetProperty("reportedX").ValueKind);
    }

    private async Task<JsonElement> UploadAsync(string path)
    {
        using var content = new ByteArrayContent(await File.ReadAllBytesAsync(path, Token));
        using var response = await _client.PostAsync($"/api/image?name={Uri.EscapeDataString(Path.GetFileName(path))}", content, Token);
        Assert.Equal(HttpStatusCode.OK, response.StatusCode);
        return await response.Content.ReadFromJsonAsync<JsonElement>(Token);
    }

    private async Task<JsonElement> PostAsync(string path, object body, HttpStatusCode expected = HttpStatusCode.OK)
    {
        using var response = await _client.PostAsJsonAsync(path, body, Token);
        Assert.Equal(expected, response.StatusCode);
        return await response.Content.ReadFromJsonAsync<JsonElement>(Token);
    }

    private Task<JsonElement> WaitForAsync(Func<JsonElement, bool> condition, TimeSpan timeout) => WaitForAsync(_client, condition, timeout);

    private static async Task<JsonElement> WaitForAsync(HttpClient client, Func<JsonElement, bool> condition, TimeSpan timeout)
    {
        var end = DateTime.UtcNow + timeout;
        while (true)
        {
            var state = await client.GetFromJsonAsync<JsonElement>("/api/state", Token);
            if (condition(state) || DateTime.UtcNow > end)
            {
                return state;
            }

            await Task.Delay(50, Token);
        }
    }

    [Fact]
    public async Task Theme_SystemLightOrDarkKept_AnotherValueRefused()
    {
        Assert.Equal("system", (await StateAsync()).GetProperty("settings").GetProperty("theme").GetString());

        var dark = await PostAsync("/api/settings/theme", new { theme = "dark" });
        var refused = await PostAsync("/api/settings/theme", new { theme = "blue" }, HttpStatusCode.BadRequest);

        Assert.Equal("dark", dark.GetProperty("settings").GetProperty("theme").GetString());
        Assert.Equal("theme 'blue': use system, light, dark", refused.GetProperty("error").GetString());
        Assert.Equal("dark", (await StateAsync()).GetProperty("settings").GetProperty("theme").GetString());
    }

    [Fact]
    public async Task Root_Get_ServesThePage()
    {
        var page = await _client.GetStringAsync("/", Token);

        Assert.Contains("<title>LaserEngrave</title>", page, StringComparison.Ordinal);
        Assert.Contains("_framework/blazor.web", page, StringComparison.Ordinal);
        Assert.Contains("boot", page, StringComparison.Ordinal);
        // Not prerendered: the workspace comes over the page's connection, which shows the token.
        Assert.DoesNotContain("id=\"stage-host\"", page, StringComparison.Ordinal);
    }

    [Fact]
    public async Task State_Samples_ListsTheShippedImagesAndOneOpens()
    {
        var samples = (await StateAsync()).GetProperty("samples").EnumerateArray().Select(e => e.GetString()!).ToList();
        var qr = Assert.Single(samples, p => Path.GetFileName(p) == "qr-code.bmp");
        Assert.Contains(samples, p => Path.GetFileName(p) == "text-banner.png");

        await PostAsync("/api/image/open", new { path = qr });

        var state = await WaitForAsync(s => s.GetProperty("image").GetProperty("path").GetString() == qr, TimeSpan.FromSeconds(10));
        Assert.Equal(41, state.GetProperty("image").GetProperty("info").GetProperty("width").GetInt32());
    }


    [Fact]
    public async Task OpenImage_SlowToRead_ReadInTheBackgroundWithItsProgressAndAnsweredOnceOpen()
    {
        var images = new GatedImages { GatedName = "text-banner.png" };
        using var app = new AppFactory(s => s.AddSingleton<App.Services.IImageService>(images));
        using var client = app.NewClient();
        var banner = TestFiles.Asset("text-banner.png");

        var opening = client.PostAsJsonAsync("/api/image/open", new { path = banner }, Token);

        // Another request is answered meanwhile, and the state says what is being read.
        var during = await WaitForAsync(client, s => s.GetProperty("image").GetProperty("loading").GetString() is not null, TimeSpan.FromSeconds(20));
        Assert.Equal("Reading text-banner.png…", during.GetProperty("image").GetProperty("loading").GetString());
        Assert.False(opening.IsCompleted);
        images.Gate.SetResult();
        using var response = await opening.WaitAsync(TimeSpan.FromSeconds(30), Token);
        var state = await response.Content.ReadFromJsonAsync<JsonElement>(Token);
        Assert.Equal(banner, state.GetProperty("image").GetProperty("path").GetString());
        Assert.Equal(JsonValueKind.Null, state.GetProperty("image").GetProperty("loading").ValueKind);
    }

    [Fact]
    public async Task Upload_Asset_StateHasImageMaskAndEstimate()
    {
        var state = await UploadAsync(TestFiles.Asset("qr-code.bmp"));

        Assert.Equal(41, state.GetProperty("image").GetProperty("info").GetProperty("width").GetInt32());
        Assert.True(state.GetProperty("estimate").GetProperty("seconds").GetDouble() > 0);
        using var mask = await _client.GetAsync("/api/image/mask.png", Token);
        Assert.Equal("image/png", mask.Content.Headers.ContentType!.MediaType);
    }

    [Theory]
    [InlineData("application/x-www-form-urlencoded")]
    [InlineData("image/bmp")]
    [InlineData("application/octet-stream")]
    public async Task Upload_AnyContentType_Opened(string contentType)
    {
        // curl --data-binary sends a form's content type; the upload takes the body's bytes whatever it is called.
        using var content = new ByteArrayContent(await File.ReadAllBytesAsync(TestFiles.Asset("qr-code.bmp"), Token));
        content.Headers.ContentType = new(contentType);

        using var response = await _client.PostAsync("/api/image?name=qr-code.bmp", content, Token);

        Assert.Equal(HttpStatusCode.OK, response.StatusCode);
    }

    [Fact]
    public async Task Upload_SameNameTwiceOtherBytes_TheFirstFileKeptAsItWas()
    {
        using var one = TestFiles.NewFolder();
        using var two = TestFiles.NewFolder();
        var first = File.ReadAllBytes(TestFiles.WriteChecker(one.Path, 8, 6));
        var second = File.ReadAllBytes(TestFiles.WriteChecker(two.Path, 10, 4));
        Assert.NotEqual(first, second);

        foreach (var bytes in new[] { first, second })
        {
            using var content = new ByteArrayContent(bytes);
            using var response = await _client.PostAsync("/api/image?name=same.png", content, Token);
            Assert.Equal(HttpStatusCode.OK, response.StatusCode);
        }

        var kept = Directory.GetFiles(Path.Combine(_app.DataFolder, "images"), "same.png", SearchOption.AllDirectories);
        Assert.Equal(2, kept.Length);
        Assert.Contains(kept, f => File.ReadAllBytes(f).SequenceEqual(first));
        Assert.Contains(kept, f => File.ReadAllBytes(f).SequenceEqual(second));
    }

    [Fact]
    public async Task Upload_NotAnImage_ErrorBesideImage()
    {
        using var folder = TestFiles.NewFolder();
        var path = Path.Combine(folder.Path, "notes.png");
        await File.WriteAllTextAsync(path, "hello", Token);

        var state = await UploadAsync(path);

        // The user's file by the name it had, never the app's copy of it in images/.
        var error = state.GetProperty("job").GetProperty("errors").GetProperty("image").GetString();
        Assert.StartsWith("notes.png: not a BMP, PNG", error, StringComparison.Ordinal);
        Assert.DoesNotContain(_app.DataFolder, error, StringComparison.Ordinal);
        Assert.Equal(JsonValueKind.Null, state.GetProperty("estimate").ValueKind);
        // Only files that open stay in images/.
        Assert.Empty(Directory.GetFileSystemEntries(Path.Combine(_app.DataFolder, "images")));
    }

    [Theory]
    [InlineData("a\0b.png", "a?b.png: the name has a character a file name cannot have")]
    [InlineData("..", "..: not a file name")]
    [InlineData(".", ".: not a file name")]
    [InlineData("LONG", "the name is longer than 200 characters")]
    [InlineData("a\\b.png", "a\\b.png: a path, not a file name: send the file's name alone")]
    [InlineData("../../x.png", "../../x.png: a path, not a file name: send the file's name alone")]
    [InlineData("CON", "CON: a name Windows keeps for a device (CON, NUL, AUX, COM1, LPT1...)")]
    [InlineData("NUL", "NUL: a name Windows keeps for a device (CON, NUL, AUX, COM1, LPT1...)")]
    [InlineData("COM1", "COM1: a name Windows keeps for a device (CON, NUL, AUX, COM1, LPT1...)")]
    [InlineData("aux.bmp", "aux.bmp: a name Windows keeps for a device (CON, NUL, AUX, COM1, LPT1...)")]
    [InlineData("scan.png.", "scan.png.: the name ends in a dot or a space, which Windows drops")]
    [InlineData("scan.png ", "scan.png : the name ends in a dot or a space, which Windows drops")]
    [InlineData("gnp.\u202Eevil.exe", "gnp.?evil.exe: the name has an invisible formatting character (U+202E), which can make it read as another name")]
    [InlineData("a:b.png", "a:b.png: the name has a character a file name cannot have")]
    public async Task Upload_OddName_OneClearBadRequestAndNothingKept(string name, string error)
    {
        name = name == "LONG" ? new string('a', 296) + ".png" : name;
        using var content = new ByteArrayContent(await File.ReadAllBytesAsync(TestFiles.Asset("qr-code.bmp"), Token));

        using var response = await _client.PostAsync($"/api/image?name={Uri.EscapeDataString(name)}", content, Token);

        Assert.Equal(HttpStatusCode.BadRequest, response.StatusCode);
        var message = (await response.Content.ReadFromJsonAsync<JsonElement>(Token)).GetProperty("error").GetString()!;
        Assert.EndsWith(error, message, StringComparison.Ordinal);
        Assert.DoesNotContain('\n', message);
        Assert.DoesNotContain(_app.DataFolder, message, StringComparison.Ordinal);
        var images = Path.Combine(_app.DataFolder, "images");
        Assert.Empty(Directory.Exists(images) ? Directory.GetFileSystemEntries(images) : []);
    }

    [Fact]
    public async Task OpenImage_AnyOtherFile_ErrorNamesTheFileNeverItsContent()
    {
        using var folder = TestFiles.NewFolder();
        var path = Path.Combine(folder.Path, "passwd");
        await File.WriteAllTextAsync(path, "root:x:0:0:root:/root:/bin/bash\n", Token);

        var state = await PostAsync("/api/image/open", new { path });

        var error = state.GetProperty("job").GetProperty("errors").GetProperty("image").GetString()!;
        Assert.Equal($"{path}: not a BMP, PNG, GIF, JPEG, TIFF, WebP or Netpbm image", error);
        Assert.DoesNotContain("726F6F74", state.ToString(), StringComparison.OrdinalIgnoreCase);
        Assert.DoesNotContain("root:x", state.ToString(), StringComparison.Ordinal);
    }

    [Fact]
    public async Task EditJob_Width_EstimateAndHeightFollow()
    {
        var before = (await UploadAsync(TestFiles.Asset("qr-code.bmp"))).GetProperty("estimate").GetProperty("seconds").GetDouble();

        var state = await PostAsync("/api/job", new { widthMm = 2.5 });

        Assert.Equal(2.5, state.GetProperty("job").GetProperty("heightMm").GetDouble(), 3);
        Assert.NotEqual(before, state.GetProperty("estimate").GetProperty("seconds").GetDouble());
    }

    [Fact]
    public async Task EditJob_TextForNumber_BadRequestNamingField()
    {
        await UploadAsync(TestFiles.Asset("qr-code.bmp"));

        var answer = await PostAsync("/api/job", new { burnSpeedMmPerS = "fast" }, HttpStatusCode.BadRequest);

        Assert.Contains("burnSpeedMmPerS", answer.GetProperty("errors").GetProperty("burnSpeedMmPerS").GetString(), StringComparison.Ordinal);
    }

    [Fact]
    public async Task EditJob_PulseEnergyBelowZero_400WithTheRulesSentenceAndNullForNotKnown()
    {
        // Issue 35: the API (as the page) once dropped a pulse energy of 0 or below without a word; the command line refused it.
        await UploadAsync(TestFiles.Asset("qr-code.bmp"));

        var refused = await PostAsync("/api/job", new { pulseEnergyUj = -5 }, HttpStatusCode.BadRequest);
        var cleared = await PostAsync("/api/job", new Dictionary<string, object?> { ["pulseEnergyUj"] = null });

        Assert.Equal("pulse energy -5 µJ: must be a finite number above 0 (or left out: not known)", refused.GetProperty("errors").GetProperty("pulseEnergyUj").GetString());
        Assert.Equal(JsonValueKind.Null, cleared.GetProperty("job").GetProperty("pulseEnergyUj").ValueKind);
        Assert.Empty(cleared.GetProperty("job").GetProperty("errors").EnumerateObject());
    }

    [Fact]
    public async Task EditJob_OriginPuttingTheJobOffTheTravel_400WithTheSentenceTheDropAndTheCommandLineSay()
    {
        await UploadAsync(TestFiles.Asset("qr-code.bmp"));

        var refused = await PostAsync("/api/job", new { widthMm = 10, originXMm = 55, originYMm = 1 }, HttpStatusCode.BadRequest);

        var error = refused.GetProperty("errors").GetProperty("originXMm").GetString();
        Assert.StartsWith("the job (10 x ", error, StringComparison.Ordinal);
        Assert.EndsWith("mm at origin 55, 1 mm) does not fit the stage's travel (60 x 60 mm): move the origin or make it smaller", error, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("/api/moves/fire", """{"pulses":1000001}""", "test fire of 1000001 pulses: must be 1..1000000 pulses (the laser gate's burst range)")]
    [InlineData("/api/moves/fire", """{"pulses":0}""", "test fire of 0 pulses: must be 1..1000000 pulses (the laser gate's burst range)")]
    [InlineData("/api/moves/jog", """{"direction":"y+","stepUm":70000}""", "step 70000 µm: longer than the Y travel (60000 µm)")]
    [InlineData("/api/moves/goto", """{"xMm":61,"yMm":0}""", "go to X 61 mm: outside the travel 0..60 mm")]
    public async Task Moves_OutsideTheRules_400WithTheRulesSentenceNothingStarted(string path, string body, string expected)
    {
        // Issue 35: these once answered 202 and failed (or, past 100,000 pulses, were refused by the app alone) afterwards.
        using var content = new StringContent(body, System.Text.Encoding.UTF8, "application/json");
        using var response = await _client.PostAsync(path, content, Token);

        Assert.Equal(HttpStatusCode.BadRequest, response.StatusCode);
        Assert.Equal(expected, (await response.Content.ReadFromJsonAsync<JsonElement>(Token)).GetProperty("error").GetString());
    }

    [Fact]
    public async Task Plan_AfterUpload_MovesMatchTheEstimate()
    {
        var state = await UploadAsync(TestFiles.Asset("qr-code.bmp"));

        var plan = await _client.GetFromJsonAsync<JsonElement>("/api/plan", Token);

        Assert.Equal(state.GetProperty("estimate").GetProperty("moves").GetInt64() * 5, plan.GetProperty("moves").GetArrayLength());
        Assert.False(plan.GetProperty("truncated").GetBoolean());
    }

    [Fact]
    public async Task Plan_DotMode_OneStrokeADotAsManyAsTheRunCounts()
    {
        await UploadAsync(TestFiles.Asset("qr-code.bmp"));

        var state = await PostAsync("/api/job", new { mode = "dots", pulsesPerDot = 10 }, HttpStatusCode.OK);
        var plan = await _client.GetFromJsonAsync<JsonElement>("/api/plan", Token);

        // The QR code's 563 black pixels: 563 dots, each a burn stroke (kind 1) centred on its pixel.
        Assert.Equal("Dots", state.GetProperty("job").GetProperty("mode").GetString());
        Assert.Equal(563, state.GetProperty("estimate").GetProperty("moves").GetInt64());
        Assert.Equal(563 * 5, plan.GetProperty("moves").GetArrayLength());
        Assert.Equal(1, plan.GetProperty("moves")[0].GetInt64());
    }

    [Fact]
    public async Task StateAndPlan_DrawingOpen_EstimateAndTheMovesOfItsStrokes()
    {
        // Issue 35: with hexagons.dxf open, /api/state gave estimate null and /api/plan no move.
        var state = await PostAsync("/api/image/open", new { path = TestFiles.Asset(Path.Combine("drawings", "hexagons.dxf")) });
        var plan = await _client.GetFromJsonAsync<JsonElement>("/api/plan", Token);

        var estimate = state.GetProperty("estimate");
        Assert.True(estimate.GetProperty("seconds").GetDouble() > 0, estimate.ToString());
        Assert.Equal("stroke", estimate.GetProperty("unit").GetString());
        var strokes = estimate.GetProperty("rows").GetInt32();
        Assert.True(strokes > 0);
        Assert.True(estimate.GetProperty("fitsTravel").GetBoolean());
        var moves = plan.GetProperty("moves").EnumerateArray().Select(m => m.GetInt64()).ToList();
        Assert.Equal(0, moves.Count % 5);
        Assert.True(Enumerable.Range(0, moves.Count / 5).Count(i => moves[i * 5] == (long)Core.Planning.MoveKind.Burn) >= strokes);
        var box = plan.GetProperty("job");
        Assert.True(box.GetProperty("right").GetInt64() > box.GetProperty("left").GetInt64());
        Assert.True(box.GetProperty("bottom").GetInt64() > box.GetProperty("top").GetInt64());
    }

    [Fact]
    public async Task RunStart_AllWhiteImage_409WithTheReasonAndNothingRuns()
    {
        // Issue 35: the app refused it, the API answered that refusal 202 with the state Failed.
        using var folder = TestFiles.NewFolder();
        var white = Path.Combine(folder.Path, "white.bmp");
        using (var file = File.Create(white))
        {
            Core.Imaging.BmpMaskWriter.Write(file, new Core.Imaging.BitMask(8, 6));
        }

        await UploadAsync(white);
        await PostAsync("/api/job", new { widthMm = 0.8, originXMm = 0, originYMm = 0 });
        await PostAsync("/api/machine/connect", new { useSimulator = true }, HttpStatusCode.Accepted);
        await WaitForAsync(s => s.GetProperty("machine").GetProperty("connected").GetBoolean() && !s.GetProperty("activity").GetProperty("busy").GetBoolean(), TimeSpan.FromSeconds(20));

        var answer = await PostAsync("/api/run/start", new { sampleId = "W-1" }, HttpStatusCode.Conflict);

        var error = answer.GetProperty("error").GetString()!;
        Assert.Contains("white.bmp: the mask has no pixel to burn", error, StringComparison.Ordinal);
        var state = await StateAsync();
        Assert.Equal("Idle", state.GetProperty("run").GetProperty("state").GetString());
        Assert.Empty(state.GetProperty("log").GetProperty("history").EnumerateArray());
    }

    [Fact]
    public async Task Connect_PortsWithoutNames_ErrorShown()
    {
        await PostAsync("/api/machine/connect", new { useSimulator = false }, HttpStatusCode.Accepted);

        var state = await WaitForAsync(s => s.GetProperty("machine").GetProperty("error").ValueKind == JsonValueKind.String, TimeSpan.FromSeconds(10));

        Assert.Equal("no port chosen for the stage", state.GetProperty("machine").GetProperty("error").GetString());
    }

    [Fact]
    public async Task Run_SmallImageOnSimulator_CompletesLogsAndExports()
    {
        using var folder = TestFiles.NewFolder();
        await UploadAsync(TestFiles.WriteChecker(folder.Path, 8, 6));
        await PostAsync("/api/job", new { widthMm = 0.8, originXMm = 0, originYMm = 0 });
        await PostAsync("/api/machine/connect", new { useSimulator = true }, HttpStatusCode.Accepted);
        await WaitForAsync(s => s.GetProperty("machine").GetProperty("connected").GetBoolean() && !s.GetProperty("activity").GetProperty("busy").GetBoolean(), TimeSpan.FromSeconds(20));

        await PostAsync("/api/run/start", new { notes = "api test", sampleId = "T-1" }, HttpStatusCode.Accepted);
        var state = await WaitForAsync(s => !s.GetProperty("run").GetProperty("active").GetBoolean() && s.GetProperty("run").GetProperty("state").GetString() != "Idle", TimeSpan.FromSeconds(120));

        var run = state.GetProperty("run");
        Assert.True("Completed" == run.GetProperty("state").GetString(), run.ToString());
        Assert.Equal(run.GetProperty("movesTotal").GetInt64(), run.GetProperty("movesDone").GetInt64());
        var last = state.GetProperty("log").GetProperty("lastRun");
        Assert.Equal("T-1", last.GetProperty("sampleId").GetString());
        var path = last.GetProperty("path").GetString()!;
        Assert.StartsWith(_app.DataFolder, path, StringComparison.Ordinal);
        var text = await _client.GetStringAsync($"/api/logs/export?format=txt&path={Uri.EscapeDataString(path)}", Token);
        Assert.Contains("Sample:             T-1", text, StringComparison.Ordinal);
        var json = await _client.GetFromJsonAsync<JsonElement>($"/api/logs/export?format=json&path={Uri.EscapeDataString(path)}", Token);
        Assert.Equal("completed", json.GetProperty("outcome").GetString(), ignoreCase: true);
        Assert.Single(state.GetProperty("log").GetProperty("history").EnumerateArray());

        // The two CSV variants download under their own names (the second no longer replaces or renames the first).
        _app.Services.GetRequiredService<MainViewModel>().Log.SelectShownCommand.Execute(null);
        using var point = await _client.GetAsync("/api/logs/history?format=csv&decimalMark=point", Token);
        using var comma = await _client.GetAsync("/api/logs/history?format=csv&decimalMark=comma", Token);
        var pointName = point.Content.Headers.ContentDisposition!.FileName!.Trim('"');
        var commaName = comma.Content.Headers.ContentDisposition!.FileName!.Trim('"');
        Assert.EndsWith(".csv", pointName, StringComparison.Ordinal);
        Assert.EndsWith("-decimal-comma.csv", commaName, StringComparison.Ordinal);
        Assert.NotEqual(pointName, commaName);
        Assert.Contains(";", await comma.Content.ReadAsStringAsync(Token), StringComparison.Ordinal);
    }

    [Fact]
    public async Task JobFile_SingleImage_DownloadedSavedAndOpenedBackAsTheSingleJob()
    {
        using var folder = TestFiles.NewFolder();
        using (var none = await _client.GetAsync("/api/jobfile", Token))
        {
            Assert.Equal(HttpStatusCode.Conflict, none.StatusCode);
        }

        await UploadAsync(TestFiles.WriteChecker(folder.Path, 8, 6));
        await PostAsync("/api/job", new { widthMm = 4, originXMm = 2, originYMm = 3 });

        using var download = await _client.GetAsync("/api/jobfile", Token);
        Assert.Equal(HttpStatusCode.OK, download.StatusCode);
        using var json = JsonDocument.Parse(await download.Content.ReadAsStringAsync(Token));
        var layer = Assert.Single(json.RootElement.GetProperty("layers").EnumerateArray());
        Assert.True(Path.IsPathFullyQualified(layer.GetProperty("source").GetString()!));
        Assert.Equal(4, layer.GetProperty("widthMm").GetDouble());
        var path = Path.Combine(folder.Path, "checker.json");
        await PostAsync("/api/jobfile/save", new { path });
        await PostAsync("/api/job", new { widthMm = 6 });

        await PostAsync("/api/jobfile/open", new { path });

        var main = _app.Services.GetRequiredService<MainViewModel>();
        Assert.Equal(4, main.Job.WidthMm);
        Assert.Empty(main.Layers.Layers);
        var bad = await PostAsync("/api/jobfile/open", new { path = Path.Combine(folder.Path, "none.json") }, HttpStatusCode.BadRequest);
        Assert.Contains("none.json", bad.GetProperty("error").GetString(), StringComparison.Ordinal);
    }

    [Fact]
    public async Task RunStart_PixelsMuchSmallerThanTheSpot_409WithTheQuestionUnlessConfirmed()
    {
        using var folder = TestFiles.NewFolder();
        await UploadAsync(TestFiles.WriteChecker(folder.Path, 8, 6));
        await PostAsync("/api/job", new { pitchUm = 5, originXMm = 0, originYMm = 0, burnSpeedMmPerS = 0.4 });
        await PostAsync("/api/machine/connect", new { useSimulator = true }, HttpStatusCode.Accepted);
        await WaitForAsync(s => s.GetProperty("machine").GetProperty("connected").GetBoolean() && !s.GetProperty("activity").GetProperty("busy").GetBoolean(), TimeSpan.FromSeconds(20));

        var answer = await PostAsync("/api/run/start", new { sampleId = "T-2" }, HttpStatusCode.Conflict);

        var question = answer.GetProperty("error").GetString();
        Assert.StartsWith("Start anyway? Its pixels of 5 µm are much smaller than the 20 µm laser spot", question, StringComparison.Ordinal);
        Assert.EndsWith("Send \"confirm\": true to start anyway", question, StringComparison.Ordinal);
        await PostAsync("/api/run/start", new { sampleId = "T-2", confirm = true }, HttpStatusCode.Accepted);
        var state = await WaitForAsync(s => !s.GetProperty("run").GetProperty("active").GetBoolean() && s.GetProperty("run").GetProperty("state").GetString() != "Idle", TimeSpan.FromSeconds(120));
        Assert.True("Completed" == state.GetProperty("run").GetProperty("state").GetString(), state.GetProperty("run").ToString());
    }

    [Fact]
    public async Task RunStart_SpeedThisComputerCannotHoldOnAFrequencyOnlyGate_409WithTheSpeedFieldsSentence()
    {
        // Issue 34: 1.5 µm of tolerance over a lab PC's 0.5 ms holds 3 mm/s on a gate the host times; 4 is refused before anything moves.
        using var folder = TestFiles.NewFolder();
        var profilePath = TestFiles.Asset(Path.Combine("profiles", "frequency-only.json"));
        _app.Services.GetRequiredService<MainViewModel>().UseProfile(profilePath, MachineProfile.Load(profilePath) with { EdgeToleranceUm = 1.5 });
        await UploadAsync(TestFiles.WriteChecker(folder.Path, 8, 6));
        // The job keeps the speed, as the page's field does, and the edit answers the rule's refusal.
        await PostAsync("/api/job", new { widthMm = 5, originXMm = 0, originYMm = 0, burnSpeedMmPerS = 4 }, HttpStatusCode.BadRequest);
        await PostAsync("/api/machine/connect", new { useSimulator = true }, HttpStatusCode.Accepted);
        await WaitForAsync(s => s.GetProperty("machine").GetProperty("connected").GetBoolean() && !s.GetProperty("activity").GetProperty("busy").GetBoolean(), TimeSpan.FromSeconds(20));

        var answer = await PostAsync("/api/run/start", new { sampleId = "T-4", acceptNoWatchdog = true, confirm = true }, HttpStatusCode.Conflict);

        Assert.Equal(
            "burn speed 4 mm/s: faster than this computer can hold with this gate: it wakes up to 0.5 ms late (the profile's latency.hostLatenessMs), 2 µm at 4 mm/s, past the edge tolerance of 1.5 µm; the fastest it holds is 3 mm/s (a gate that times its switch-ons, CAPS? listing AFTER, holds any)",
            answer.GetProperty("error").GetString());
    }

    [Fact]
    public async Task RunStart_GateWithoutWatchdog_409WithTheSentenceUntilAcceptedThenTheLogKeepsIt()
    {
        using var folder = TestFiles.NewFolder();
        var profilePath = TestFiles.Asset(Path.Combine("profiles", "frequency-only.json"));
        _app.Services.GetRequiredService<MainViewModel>().UseProfile(profilePath, MachineProfile.Load(profilePath));
        await UploadAsync(TestFiles.WriteChecker(folder.Path, 8, 6));
        await PostAsync("/api/job", new { widthMm = 0.8, originXMm = 0, originYMm = 0 });
        await PostAsync("/api/machine/connect", new { useSimulator = true }, HttpStatusCode.Accepted);
        await WaitForAsync(s => s.GetProperty("machine").GetProperty("connected").GetBoolean() && !s.GetProperty("activity").GetProperty("busy").GetBoolean(), TimeSpan.FromSeconds(20));

        var answer = await PostAsync("/api/run/start", new { sampleId = "T-3" }, HttpStatusCode.Conflict);

        Assert.StartsWith(LaserGateProfile.NoWatchdogSentence, answer.GetProperty("error").GetString(), StringComparison.Ordinal);
        await PostAsync("/api/run/start", new { sampleId = "T-3", acceptNoWatchdog = true }, HttpStatusCode.Accepted);
        var state = await WaitForAsync(s => !s.GetProperty("run").GetProperty("active").GetBoolean() && s.GetProperty("run").GetProperty("state").GetString() != "Idle", TimeSpan.FromSeconds(120));
        Assert.True("Completed" == state.GetProperty("run").GetProperty("state").GetString(), state.GetProperty("run").ToString());
        var path = state.GetProperty("log").GetProperty("lastRun").GetProperty("path").GetString()!;
        Assert.Equal(LaserGateProfile.NoWatchdogSentence, RunLogStore.Read(path).NoWatchdogAccepted);
    }

    [Fact]
    public async Task HistoryExport_NothingTicked_NotFoundSayingSo()
    {
        using var response = await _client.GetAsync("/api/logs/history?format=csv", Token);

        Assert.Equal(HttpStatusCode.NotFound, response.StatusCode);
        Assert.Contains("tick the runs to export first", await response.Content.ReadAsStringAsync(Token), StringComparison.Ordinal);
    }

    [Fact]
    public async Task Export_FileNotInHistory_NotFound()
    {
        using var response = await _client.GetAsync("/api/logs/export?format=json&path=%2Fetc%2Fpasswd", Token);

        Assert.Equal(HttpStatusCode.NotFound, response.StatusCode);
    }

    [Fact]
    public async Task OpenImage_Fifo_RefusedAtOnceNotARegularFile()
    {
        using var folder = TestFiles.NewFolder();
        var fifo = Path.Combine(folder.Path, "image.png");
        using (var mkfifo = System.Diagnostics.Process.Start("mkfifo", [fifo]))
        {
            await mkfifo.WaitForExitAsync(Token);
        }

        // Before, opening the FIFO blocked the request for ever; the bound only keeps a broken test from hanging.
        var state = await PostAsync("/api/image/open", new { path = fifo }).WaitAsync(TimeSpan.FromSeconds(60), Token);

        Assert.Equal($"{fifo}: is a named pipe (FIFO), not a regular file", state.GetProperty("job").GetProperty("errors").GetProperty("image").GetString());
        Assert.Equal(JsonValueKind.Null, state.GetProperty("image").GetProperty("path").ValueKind);
    }
}
