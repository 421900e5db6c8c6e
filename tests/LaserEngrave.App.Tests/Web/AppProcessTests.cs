using System.Diagnostics;
using System.Net;
using System.Net.Http.Json;
using System.Net.WebSockets;
using System.Text.Json;
using System.Text.RegularExpressions;

namespace LaserEngrave.App.Tests.Web;

/// <summary>The app as a user starts it: its own process, its start line, its refusals and its exit on SIGTERM.</summary>
public sealed partial class AppProcessTests : IDisposable
{
    // Only a bound that stops a broken test from hanging; the app must do far better (2 s).
    private static readonly TimeSpan Bound = TimeSpan.FromSeconds(60);

    private readonly TestFiles.TempFolder _data = TestFiles.NewFolder();
    private Process? _process;

    private static CancellationToken Token => TestContext.Current.CancellationToken;

    public void Dispose()
    {
        if (_process is { HasExited: false })
        {
            _process.Kill(entireProcessTree: true);
        }

        _process?.Dispose();
        _data.Dispose();
    }

    /// <summary>Sends SIGTERM the way a service manager does (SIGHUP: a terminal closing; SIGQUIT: Ctrl+\\).</summary>
    private static async Task TerminateAsync(Process process, string signal = "TERM")
    {
        using var kill = Process.Start("kill", [$"-{signal}", process.Id.ToString(System.Globalization.CultureInfo.InvariantCulture)]);
        await kill.WaitForExitAsync(Token);
        Assert.Equal(0, kill.ExitCode);
    }

    /// <summary>
    /// The app's arguments for a run on its simulator that starts near home (the simulator's --sim-options), so the
    /// homing before a run takes a fraction of a second at the machine's pace instead of 15 s from the far end.
    /// </summary>
    private string[] NearHome()
    {
        var file = Path.Combine(_data.Path, "near-home.json");
        File.WriteAllText(file, "{ \"startMm\": 0.5 }");
        return ["--urls", "http://127.0.0.1:0", "--sim-options", file];
    }

    [GeneratedRegex(@"^LaserEngrave is running at (http://127\.0\.0\.1:\d+)(/#launch=[A-Za-z0-9_-]{22}| \(in its own window\))$")]
    private static partial Regex StartLine();

    private Process Start(string[] args, params (string Key, string Value)[] environment) => Start(args, browser: false, environment);

    private Process Start(string[] args, bool browser, params (string Key, string Value)[] environment)
    {
        var start = new ProcessStartInfo("dotnet")
        {
            RedirectStandardOutput = true,
            RedirectStandardError = true,
            UseShellExecute = false,
        };
        start.ArgumentList.Add(Path.Combine(AppContext.BaseDirectory, "LaserEngrave.App.dll"));
        if (!browser)
        {
            start.ArgumentList.Add("--no-browser");
        }

        start.ArgumentList.Add("--data-folder");
        start.ArgumentList.Add(_data.Path);
        foreach (var arg in args)
        {
            start.ArgumentList.Add(arg);
        }

        start.Environment.Remove("ASPNETCORE_URLS");
        start.Environment["DOTNET_ENVIRONMENT"] = "Production";
        foreach (var (key, value) in environment)
        {
            start.Environment[key] = value;
        }

        _process = Process.Start(start)!;
        return _process;
    }

    /// <summary>The address on the start line and the token in connection.json (the start line carries a launch code, never the token).</summary>
    private async Task<(string Base, string Secret)> ReadStartLineAsync(Process process)
    {
        var line = await process.StandardOutput.ReadLineAsync(Token).AsTask().WaitAsync(Bound, Token);
        var match = StartLine().Match(line ?? string.Empty);
        Assert.True(match.Success, $"start line: {line}; stderr: {(process.HasExited ? await process.StandardError.ReadToEndAsync(Token) : string.Empty)}");
        var connection = JsonDocument.Parse(await File.ReadAllTextAsync(Path.Combine(_data.Path, "connection.json"), Token)).RootElement;
        return (match.Groups[1].Value, connection.GetProperty("token").GetString()!);
    }

    [Theory]
    [InlineData("--urls", "http://127.0.0.1:1;http://0.0.0.0:2", "http://0.0.0.0:2")]
    [InlineData("--urls=http://0.0.0.0:5099", null, "http://0.0.0.0:5099")]
    public async Task Start_NetworkAddressInOptions_RefusedWithOneLineExit2(string option, string? value, string named)
    {
        var process = Start(value is null ? [option] : [option, value]);

        await process.WaitForExitAsync(Token).WaitAsync(Bound, Token);

        var error = await process.StandardError.ReadToEndAsync(Token);
        Assert.Equal(2, process.ExitCode);
        Assert.Contains(named, error, StringComparison.Ordinal);
        Assert.Single(error.Split('\n', StringSplitOptions.RemoveEmptyEntries));
        Assert.DoesNotContain("running at", await process.StandardOutput.ReadToEndAsync(Token), StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("https://127.0.0.1:5443")]
    [InlineData("http://127.0.0.1:5444;https://localhost:5445")]
    public async Task Start_HttpsAddress_OneLineExit2(string urls)
    {
        var process = Start(["--urls", urls]);

        await process.WaitForExitAsync(Token).WaitAsync(Bound, Token);

        var error = await process.StandardError.ReadToEndAsync(Token);
        Assert.Equal(2, process.ExitCode);
        Assert.Contains("the app listens over http:// only", Assert.Single(error.Split('\n', StringSplitOptions.RemoveEmptyEntries)), StringComparison.Ordinal);
        Assert.Empty(await process.StandardOutput.ReadToEndAsync(Token));
    }

    [Fact]
    public async Task Start_PortInUse_OneLineExit2()
    {
        using var other = new System.Net.Sockets.TcpListener(IPAddress.Loopback, 0);
        other.Start();
        var port = ((IPEndPoint)other.LocalEndpoint).Port;
        var process = Start(["--urls", $"http://127.0.0.1:{port}"]);

        await process.WaitForExitAsync(Token).WaitAsync(Bound, Token);

        var error = await process.StandardError.ReadToEndAsync(Token);
        Assert.Equal(2, process.ExitCode);
        Assert.Equal($"Failed to bind to address http://127.0.0.1:{port}: address already in use.", Assert.Single(error.Split('\n', StringSplitOptions.RemoveEmptyEntries)));
        Assert.Empty(await process.StandardOutput.ReadToEndAsync(Token));
    }

    [Fact]
    public async Task Start_IPv4MappedAddress_OneLineExit2()
    {
        var process = Start(["--urls", "http://[::ffff:127.0.0.1]:5097"]);

        await process.WaitForExitAsync(Token).WaitAsync(Bound, Token);

        var error = await process.StandardError.ReadToEndAsync(Token);
        Assert.Equal(2, process.ExitCode);
        Assert.StartsWith("http://[::ffff:127.0.0.1]:5097 (--urls) is an IPv4 address written as IPv6", Assert.Single(error.Split('\n', StringSplitOptions.RemoveEmptyEntries)), StringComparison.Ordinal);
    }

    [Fact]
    public async Task Start_ConnectionFile_AddressAndTokenReadableByTheUserAloneRemovedAtExit()
    {
        var process = Start(["--urls", "http://127.0.0.1:0"]);
        var (address, secret) = await ReadStartLineAsync(process);
        var file = Path.Combine(_data.Path, "connection.json");

        var connection = JsonDocument.Parse(await File.ReadAllTextAsync(file, Token)).RootElement;
        Assert.Equal(address, connection.GetProperty("url").GetString());
        Assert.Equal(secret, connection.GetProperty("token").GetString());
        Assert.Equal(process.Id, connection.GetProperty("pid").GetInt32());
        if (!OperatingSystem.IsWindows())
        {
            Assert.Equal(UnixFileMode.UserRead | UnixFileMode.UserWrite, File.GetUnixFileMode(file));
        }

        await TerminateAsync(process);
        await process.WaitForExitAsync(Token).WaitAsync(Bound, Token);
        Assert.False(File.Exists(file));
    }

    /// <summary>
    /// The window's launch as another local user sees it: a stand-in browser (a script first on PATH, named chromium)
    /// is started by the app and stays alive; its arguments, read through /proc/PID/cmdline as any user can, name no
    /// secret, and every string in them (as a token, as a launch code) is refused for the state, connect, jog and fire.
    /// The launch file they name is the user's alone; the code in it opens the page once and is refused after, as the
    /// browser's history would keep it.
    /// </summary>
    [Fact]
    [System.Runtime.Versioning.UnsupportedOSPlatform("windows")]
    public async Task Launch_StandInBrowser_ItsArgumentsOpenNothingForAnotherUser()
    {
        using var bin = TestFiles.NewFolder();
        var record = Path.Combine(bin.Path, "browser.pid");
        var standIn = Path.Combine(bin.Path, "chromium");
        await File.WriteAllTextAsync(standIn, $"#!/bin/sh\necho $$ > '{record}.part' && mv '{record}.part' '{record}'\nsleep 120\n", Token);
        File.SetUnixFileMode(standIn, UnixFileMode.UserRead | UnixFileMode.UserWrite | UnixFileMode.UserExecute);
        var process = Start(["--urls", "http://127.0.0.1:0"], browser: true, ("PATH", bin.Path + Path.PathSeparator + Environment.GetEnvironmentVariable("PATH")));
        var (address, secret) = await ReadStartLineAsync(process);
        for (var i = 0; !File.Exists(record) && i < 6000; i++)
        {
            // Only a bound for a broken test: the browser is started right after the start line.
            await Task.Delay(10, Token);
        }

        var browserPid = int.Parse((await File.ReadAllTextAsync(record, Token)).Trim(), System.Globalization.CultureInfo.InvariantCulture);
        try
        {
            // What another user reads: the browser's whole command line.
            var arguments = (await File.ReadAllTextAsync($"/proc/{browserPid}/cmdline", Token)).Split('\0', StringSplitOptions.RemoveEmptyEntries);
            var app = Assert.Single(arguments, a => a.StartsWith("--app=", StringComparison.Ordinal));
            Assert.DoesNotContain(arguments, a => a.Contains(secret, StringComparison.Ordinal));
            var launchFile = new Uri(app["--app=".Length..]).LocalPath;
            Assert.StartsWith(_data.Path, launchFile, StringComparison.Ordinal);
            var userAlone = UnixFileMode.UserRead | UnixFileMode.UserWrite | UnixFileMode.UserExecute;
            Assert.Equal(UnixFileMode.UserRead | UnixFileMode.UserWrite, File.GetUnixFileMode(launchFile));
            Assert.Equal(userAlone, File.GetUnixFileMode(Path.GetDirectoryName(launchFile)!));

            var found = arguments.SelectMany(a => a.Split('=', '#', '&', '?', '/', ',')).Append(string.Empty).Concat(arguments).Distinct().ToList();
            using var other = new HttpClient { BaseAddress = new Uri(address), Timeout = Bound };
            foreach (var candidate in found)
            {
                await AssertRefusedAsync(other, candidate);
            }

            // The user's browser: the file sends it to the page with a code, traded once for the token.
            var page = await File.ReadAllTextAsync(launchFile, Token);
            var code = Regex.Match(page, @"#launch=([A-Za-z0-9_-]+)").Groups[1].Value;
            using var user = new HttpClient { BaseAddress = new Uri(address), Timeout = Bound };
            using var trade = new HttpRequestMessage(HttpMethod.Post, "/api/session") { Headers = { { "X-LaserEngrave-Launch", code } } };
            using var traded = await user.SendAsync(trade, Token);
            Assert.Equal(HttpStatusCode.OK, traded.StatusCode);
            Assert.Equal(secret, (await traded.Content.ReadFromJsonAsync<JsonElement>(Token)).GetProperty("token").GetString());
            Assert.False(File.Exists(launchFile));
            user.DefaultRequestHeaders.Authorization = new("Bearer", secret);
            Assert.Equal(HttpStatusCode.Accepted, (await user.PostAsJsonAsync("/api/machine/connect", new { useSimulator = true }, Token)).StatusCode);

            // The code as the history keeps it: used, refused.
            await AssertRefusedAsync(other, code);
        }
        finally
        {
            using var kill = Process.Start("kill", [browserPid.ToString(System.Globalization.CultureInfo.InvariantCulture)]);
            await kill.WaitForExitAsync(Token);
        }
    }

    /// <summary>Asserts <paramref name="found"/>, shown as a token or traded as a launch code, reads and moves nothing.</summary>
    private static async Task AssertRefusedAsync(HttpClient client, string found)
    {
        using var trade = new HttpRequestMessage(HttpMethod.Post, "/api/session");
        trade.Headers.TryAddWithoutValidation("X-LaserEngrave-Launch", found);
        using var traded = await client.SendAsync(trade, Token);
        Assert.True(traded.StatusCode == HttpStatusCode.Unauthorized, $"launch code '{found}': {traded.StatusCode}");
        foreach (var (path, body) in new[] { ("/api/state", (string?)null), ("/api/machine/connect", "{\"useSimulator\":true}"), ("/api/moves/jog", "{\"direction\":\"x+\",\"stepUm\":5000}"), ("/api/moves/fire", "{\"pulses\":200}") })
        {
            foreach (var header in new[] { "Authorization", "X-LaserEngrave-Token" })
            {
                using var request = new HttpRequestMessage(body is null ? HttpMethod.Get : HttpMethod.Post, path);
                request.Headers.TryAddWithoutValidation(header, header == "Authorization" ? "Bearer " + found : found);
                if (body is not null)
                {
                    request.Content = new StringContent(body, System.Text.Encoding.UTF8, "application/json");
                }

                using var response = await client.SendAsync(request, Token);
                Assert.True(response.StatusCode is HttpStatusCode.Unauthorized or HttpStatusCode.Forbidden, $"{path} with '{found}' as {header}: {response.StatusCode}");
            }
        }
    }

    /// <summary>Runs clients/python/examples/test_grid.py with python3 and the arguments; its exit code and output.</summary>
    private static async Task<(int Exit, string Output, string Error)> RunPythonExampleAsync(params string[] args)
    {
        var start = new ProcessStartInfo("python3") { RedirectStandardOutput = true, RedirectStandardError = true, UseShellExecute = false };
        start.ArgumentList.Add(TestFiles.RepositoryFile(Path.Combine("clients", "python", "examples", "test_grid.py")));
        foreach (var arg in args)
        {
            start.ArgumentList.Add(arg);
        }

        using var python = Process.Start(start)!;
        var output = python.StandardOutput.ReadToEndAsync(Token);
        var error = python.StandardError.ReadToEndAsync(Token);
        await python.WaitForExitAsync(Token).WaitAsync(TimeSpan.FromMinutes(5), Token);
        return (python.ExitCode, await output, await error);
    }

    [Fact]
    public async Task PythonClient_TestGridOnTheSimulator_EachCellRunAndItsLogCollected()
    {
        // The twin unpaced: what is tested is the client and the cells' logs, not the run's pace on the wall clock.
        var options = Path.Combine(_data.Path, "unpaced.json");
        await File.WriteAllTextAsync(options, "{ \"startMm\": 0.5, \"paced\": false }", Token);
        var process = Start(["--urls", "http://127.0.0.1:0", "--sim-options", options]);
        await ReadStartLineAsync(process);
        using var logs = TestFiles.NewFolder();

        // The lab's script as it is shipped: the address and token from the app's connection file, a mark uploaded,
        // the simulator connected, one run a cell (burn speed a row, frequency a column), each cell's log fetched. The
        // app's twin has a realistically late host: at 2 mm/s its usual 0.5 ms is 1 µm, inside the 1.5 µm edge tolerance
        // (at 4 mm/s it is 2 µm, and a cell can fail where a switch-on comes late three times at one place).
        var (exit, output, error) = await RunPythonExampleAsync(
            "--simulator", "--connection", Path.Combine(_data.Path, "connection.json"), "--speeds", "2", "--frequencies", "1000,5000",
            "--size", "0.6", "--out", logs.Path);

        Assert.True(exit == 0, $"exit {exit}\n{output}\n{error}");
        Assert.Contains("2 of 2 cells completed", output, StringComparison.Ordinal);
        foreach (var (cell, frequency, x) in new[] { ("r0c0", 1000.0, 1.0), ("r0c1", 5000.0, 2.1) })
        {
            using var record = JsonDocument.Parse(await File.ReadAllTextAsync(Path.Combine(logs.Path, cell + ".json"), Token));
            var root = record.RootElement;
            Assert.Equal("completed", root.GetProperty("outcome").GetString(), ignoreCase: true);
            Assert.Equal("grid-" + cell, root.GetProperty("sampleId").GetString());
            Assert.Equal(frequency, root.GetProperty("process").GetProperty("laserFrequencyHz").GetDouble());
            Assert.Equal(2, root.GetProperty("process").GetProperty("burnSpeedMmPerS").GetDouble());
            Assert.Equal(x, root.GetProperty("geometry").GetProperty("originXMm").GetDouble(), 3);
        }

        Assert.Equal(3, (await File.ReadAllLinesAsync(Path.Combine(logs.Path, "summary.csv"), Token)).Length);
        Assert.Equal(2, Directory.GetFiles(Path.Combine(_data.Path, "logs"), "*.json", SearchOption.AllDirectories).Length);
    }

    /// <summary>
    /// clients/python/tests: the client gives the token to the app alone (no proxy, no redirect, loopback only, the
    /// server's proof of the token and the app's process checked first), against stand-in servers.
    /// </summary>
    [Fact]
    public async Task PythonClient_UnitTests_AllPass()
    {
        var start = new ProcessStartInfo("python3") { RedirectStandardOutput = true, RedirectStandardError = true, UseShellExecute = false };
        foreach (var arg in new[] { "-m", "unittest", "discover", "-v", "-s", TestFiles.RepositoryFile(Path.Combine("clients", "python", "tests")) })
        {
            start.ArgumentList.Add(arg);
        }

        start.Environment["PYTHONDONTWRITEBYTECODE"] = "1";
        using var python = Process.Start(start)!;
        var output = python.StandardOutput.ReadToEndAsync(Token);
        var error = python.StandardError.ReadToEndAsync(Token);
        await python.WaitForExitAsync(Token).WaitAsync(TimeSpan.FromMinutes(2), Token);

        var report = await error;
        Assert.True(python.ExitCode == 0, $"exit {python.ExitCode}\n{await output}\n{report}");
        Assert.Matches(@"Ran [1-9]\d* tests", report);
    }

    [Fact]
    public async Task PythonClient_NoApp_OneLineExit2()
    {
        using var folder = TestFiles.NewFolder();
        var missing = Path.Combine(folder.Path, "connection.json");

        var (exit, output, error) = await RunPythonExampleAsync("--connection", missing);

        Assert.Equal(2, exit);
        Assert.Equal($"test_grid: {missing}: no such file: is LaserEngrave running (it writes the file at start)?", error.TrimEnd());
        Assert.Empty(output);
    }

    [Fact]
    public async Task Start_SimulatorOptionsFile_TheTwinIsAsTheFileSays()
    {
        var file = Path.Combine(_data.Path, "old-firmware.json");
        await File.WriteAllTextAsync(file, "{ \"firmwareVersion\": 506, \"startMm\": 0.5 }", Token);
        var process = Start(["--urls", "http://127.0.0.1:0", "--sim-options", file]);
        var (address, secret) = await ReadStartLineAsync(process);
        using var client = new HttpClient { BaseAddress = new Uri(address), Timeout = Bound };
        client.DefaultRequestHeaders.Authorization = new("Bearer", secret);

        (await client.PostAsJsonAsync("/api/machine/connect", new { useSimulator = true }, Token)).EnsureSuccessStatusCode();
        // Identified and its position read: the two show up in separate updates, so one state is waited for that has both.
        var machine = default(JsonElement);
        await WaitForAsync(client, s =>
        {
            machine = s.GetProperty("machine");
            return machine.GetProperty("identity").ValueKind == JsonValueKind.String && machine.GetProperty("xMm").ValueKind == JsonValueKind.Number;
        });

        Assert.Contains("X: device 1, id 4212, firmware 5.06", machine.GetProperty("identity").GetString(), StringComparison.Ordinal);
        Assert.Equal(0.5, machine.GetProperty("xMm").GetDouble(), 3);
    }

    [Fact]
    public async Task Start_BadSimulatorOptionsFile_OneLineNamingTheFileExit2()
    {
        var file = Path.Combine(_data.Path, "bad.json");
        await File.WriteAllTextAsync(file, "{ \"firmwareVersion\": 9 }", Token);
        var process = Start(["--urls", "http://127.0.0.1:0", "--sim-options", file]);

        await process.WaitForExitAsync(Token).WaitAsync(Bound, Token);

        Assert.Equal(2, process.ExitCode);
        var error = (await process.StandardError.ReadToEndAsync(Token)).TrimEnd();
        Assert.DoesNotContain('\n', error);
        Assert.StartsWith($"{file}: firmwareVersion", error, StringComparison.Ordinal);
        Assert.Empty(await process.StandardOutput.ReadToEndAsync(Token));
    }

    [Fact]
    public async Task Start_NetworkAddressInAspNetCoreUrls_RefusedExit2()
    {
        var process = Start([], ("ASPNETCORE_URLS", "http://0.0.0.0:5098"));

        await process.WaitForExitAsync(Token).WaitAsync(Bound, Token);

        Assert.Equal(2, process.ExitCode);
        Assert.Contains("http://0.0.0.0:5098", await process.StandardError.ReadToEndAsync(Token), StringComparison.Ordinal);
    }

    [Fact]
    public async Task Start_Default_LoopbackAddressWithTokenThatTheApiRequires()
    {
        var process = Start(["--urls", "http://127.0.0.1:0"]);
        var (address, secret) = await ReadStartLineAsync(process);
        using var client = new HttpClient { BaseAddress = new Uri(address) };

        using var without = await client.GetAsync("/api/state", Token);
        client.DefaultRequestHeaders.Authorization = new("Bearer", secret);
        using var with = await client.GetAsync("/api/state", Token);

        Assert.Equal(HttpStatusCode.Unauthorized, without.StatusCode);
        Assert.Equal(HttpStatusCode.OK, with.StatusCode);
    }

    [Theory]
    [InlineData("TERM")]
    [InlineData("HUP")]
    [InlineData("QUIT")]
    public async Task Signal_RunUnderWayAndPageOpen_ExitsLaserOffAndLogWritten(string signal)
    {
        var process = Start(NearHome());
        var (address, secret) = await ReadStartLineAsync(process);
        using var client = new HttpClient { BaseAddress = new Uri(address), Timeout = Bound };
        client.DefaultRequestHeaders.Authorization = new("Bearer", secret);
        using (var image = new ByteArrayContent(await File.ReadAllBytesAsync(TestFiles.Asset("qr-code.bmp"), Token)))
        {
            (await client.PostAsync("/api/image?name=qr-code.bmp", image, Token)).EnsureSuccessStatusCode();
        }

        (await client.PostAsJsonAsync("/api/machine/connect", new { useSimulator = true }, Token)).EnsureSuccessStatusCode();
        await WaitForAsync(client, s => s.GetProperty("machine").GetProperty("connected").GetBoolean() && !s.GetProperty("activity").GetProperty("busy").GetBoolean());
        (await client.PostAsJsonAsync("/api/run/start", new { sampleId = "SIGTERM" }, Token)).EnsureSuccessStatusCode();
        await WaitForAsync(client, s => s.GetProperty("run").GetProperty("phase").GetString() == "running");
        // The page's connection (Blazor's hub, over a WebSocket, authorised by the token) stays open through the exit.
        using var page = await OpenPageConnectionAsync(address, secret);

        await TerminateAsync(process, signal);
        await process.WaitForExitAsync(Token).WaitAsync(Bound, Token);

        Assert.Equal(0, process.ExitCode);
        var log = Assert.Single(Directory.GetFiles(Path.Combine(_data.Path, "logs"), "*.json", SearchOption.AllDirectories));
        using var record = JsonDocument.Parse(await File.ReadAllTextAsync(log, Token));
        Assert.Equal("aborted", record.RootElement.GetProperty("outcome").GetString(), ignoreCase: true);
        if (record.RootElement.TryGetProperty("fault", out var fault) && fault.ValueKind == JsonValueKind.Object)
        {
            Assert.True(fault.GetProperty("laserOffConfirmed").GetBoolean());
        }
    }

    /// <summary>
    /// What an open page holds: Blazor's hub negotiated and its WebSocket open with the handshake done, as the page's
    /// script does, showing the token as SignalR's access token (a header on the negotiation, access_token on the socket).
    /// </summary>
    private static async Task<ClientWebSocket> OpenPageConnectionAsync(string address, string secret)
    {
        using var browser = new HttpClient { BaseAddress = new Uri(address), Timeout = Bound };
        (await browser.GetAsync("/", Token)).EnsureSuccessStatusCode();
        browser.DefaultRequestHeaders.Authorization = new("Bearer", secret);
        using var negotiate = await browser.PostAsync("/_blazor/negotiate?negotiateVersion=1", null, Token);
        negotiate.EnsureSuccessStatusCode();
        var connectionToken = (await negotiate.Content.ReadFromJsonAsync<JsonElement>(Token)).GetProperty("connectionToken").GetString();

        var socket = new ClientWebSocket();
        socket.Options.SetRequestHeader("Origin", address);
        await socket.ConnectAsync(new Uri($"{address.Replace("http://", "ws://", StringComparison.Ordinal)}/_blazor?id={connectionToken}&access_token={secret}"), Token);
        await socket.SendAsync("{\"protocol\":\"blazorpack\",\"version\":1}\u001e"u8.ToArray(), WebSocketMessageType.Text, endOfMessage: true, Token);
        var reply = new byte[256];
        var received = await socket.ReceiveAsync(reply, Token);
        Assert.Equal("{}\u001e", System.Text.Encoding.UTF8.GetString(reply, 0, received.Count));
        return socket;
    }

    private static async Task WaitForAsync(HttpClient client, Func<JsonElement, bool> condition)
    {
        // The state polled until the app's own progress shows it; the count only stops a broken test from hanging.
        for (var i = 0; i < 6000; i++)
        {
            var state = await client.GetFromJsonAsync<JsonElement>("/api/state", Token);
            if (condition(state))
            {
                return;
            }

            await Task.Delay(10, Token);
        }

        throw new TimeoutException("the app never reached the state");
    }

    [Fact]
    public async Task Upload_OverTheAppsLimitWithoutLength_AppsMessageNamingTheFileAndNothingLeft()
    {
        var process = Start(["--urls", "http://127.0.0.1:0"]);
        var (address, secret) = await ReadStartLineAsync(process);
        using var client = new HttpClient { BaseAddress = new Uri(address), Timeout = Bound };
        client.DefaultRequestHeaders.Authorization = new("Bearer", secret);
        using var content = new StreamContent(new ZeroStream((512L << 20) + 1));
        content.Headers.ContentLength = null;

        using var response = await client.PostAsync("/api/image?name=huge.png", content, Token);

        Assert.Equal(HttpStatusCode.RequestEntityTooLarge, response.StatusCode);
        var body = await response.Content.ReadFromJsonAsync<JsonElement>(Token);
        Assert.Equal("huge.png: the file is larger than 512 MB, the most the app takes", body.GetProperty("error").GetString());
        var images = Path.Combine(_data.Path, "images");
        Assert.Empty(Directory.Exists(images) ? Directory.GetFiles(images) : []);
    }

    /// <summary>A body of zeros of a given length, made as it is read (sent chunked: no length header to refuse early).</summary>
    private sealed class ZeroStream(long length) : Stream
    {
        private long _left = length;

        public override bool CanRead => true;

        public override bool CanSeek => false;

        public override bool CanWrite => false;

        public override long Length => throw new NotSupportedException();

        public override long Position { get => throw new NotSupportedException(); set => throw new NotSupportedException(); }

        public override int Read(byte[] buffer, int offset, int count)
        {
            var n = (int)Math.Min(count, _left);
            Array.Clear(buffer, offset, n);
            _left -= n;
            return n;
        }

        public override void Flush()
        {
        }

        public override long Seek(long offset, SeekOrigin origin) => throw new NotSupportedException();

        public override void SetLength(long value) => throw new NotSupportedException();

        public override void Write(byte[] buffer, int offset, int count) => throw new NotSupportedException();
    }
}
