using System.Diagnostics;
using System.Globalization;
using System.Text.Json;

namespace LaserEngrave.Cli.Tests;

/// <summary>A hang-up, a quit or a terminate in the middle of a run acts as Ctrl+C does: laser off first, stage stopped, log written.</summary>
public sealed class SignalTests : IDisposable
{
    // Only a bound that stops a broken test from hanging; the abort itself takes milliseconds.
    private static readonly TimeSpan Bound = TimeSpan.FromSeconds(60);

    private readonly string _logs = Path.Combine(Path.GetTempPath(), $"le-signal-{Guid.NewGuid():N}");

    public void Dispose()
    {
        if (Directory.Exists(_logs))
        {
            Directory.Delete(_logs, recursive: true);
        }
    }

    [Theory(Timeout = 120_000)]
    [InlineData("HUP")]
    [InlineData("QUIT")]
    [InlineData("TERM")]
    public async Task Engrave_SignalMidRun_AbortedLaserOffAndLogWritten(string signal)
    {
        var ct = TestContext.Current.CancellationToken;
        var dotnet = Environment.GetEnvironmentVariable("DOTNET_HOST_PATH") is { Length: > 0 } host ? host : "dotnet";
        var start = new ProcessStartInfo(dotnet)
        {
            ArgumentList =
            {
                typeof(Program).Assembly.Location, "engrave", Path.Combine(CliHarness.RepositoryRoot, "assets", "qr-code.bmp"),
                "--width-mm", "5", "--origin-mm", "10,10", "--simulate", "--passes", "100", "--json", "--log-dir", _logs,
            },
            RedirectStandardOutput = true,
            RedirectStandardError = true,
            UseShellExecute = false,
        };
        using var process = Process.Start(start)!;
        var running = new TaskCompletionSource(TaskCreationOptions.RunContinuationsAsynchronously);
        var stderr = new System.Collections.Concurrent.ConcurrentQueue<string>();
        process.ErrorDataReceived += (_, e) =>
        {
            if (e.Data is { } line)
            {
                stderr.Enqueue(line);
            }

            if (e.Data?.StartsWith("running:", StringComparison.Ordinal) == true)
            {
                running.TrySetResult();
            }
        };
        process.BeginErrorReadLine();
        var stdout = process.StandardOutput.ReadToEndAsync(ct);
        try
        {
            await running.Task.WaitAsync(Bound, ct);
            using (var kill = Process.Start("kill", [$"-{signal}", process.Id.ToString(CultureInfo.InvariantCulture)]))
            {
                await kill.WaitForExitAsync(ct);
                Assert.Equal(0, kill.ExitCode);
            }

            await process.WaitForExitAsync(ct).WaitAsync(Bound, ct);
        }
        finally
        {
            if (!process.HasExited)
            {
                process.Kill(entireProcessTree: true);
            }
        }

        // Exit 1 as for Ctrl+C (the run aborted), not 128 + the signal's number (killed before the laser went off).
        var printed = await stdout;
        Assert.True(process.ExitCode == 1, $"exit {process.ExitCode}: {string.Join(" | ", stderr)} {printed}");
        using var summary = JsonDocument.Parse(printed);
        Assert.True(summary.RootElement.GetProperty("outcome").GetString() == "aborted", printed);
        Assert.True(summary.RootElement.GetProperty("laserOnTravelCount").GetInt64() == 0, printed);
        var log = Assert.Single(Directory.GetFiles(_logs, "*.json"));
        using var record = JsonDocument.Parse(await File.ReadAllTextAsync(log, ct));
        Assert.Equal("aborted", record.RootElement.GetProperty("outcome").GetString());
        Assert.True(record.RootElement.GetProperty("fault").GetProperty("laserOffConfirmed").GetBoolean());
        Assert.Equal(JsonValueKind.Number, record.RootElement.GetProperty("stoppedAt").GetProperty("xMicrosteps").ValueKind);
    }
}
