namespace LaserEngrave.Cli.Tests;

/// <summary>The hidden --sim-wire: the twin's wire traffic as a flight recording, which tools/wire-capture.sh compares between builds.</summary>
public sealed class SimWireTests : IDisposable
{
    private readonly string folder = Path.Combine(Path.GetTempPath(), $"le-cli-simwire-{Guid.NewGuid():N}");

    public SimWireTests() => Directory.CreateDirectory(folder);

    private static string QrCode => Path.Combine(CliHarness.RepositoryRoot, "assets", "qr-code.bmp");

    [Fact]
    public async Task Engrave_SimWireTwice_SameRecordingBothPortsWrittenAndEnded()
    {
        var first = Path.Combine(folder, "a.jsonl");
        var second = Path.Combine(folder, "b.jsonl");

        var a = await CliHarness.RunAsync("engrave", QrCode, "--width-mm", "2", "--simulate", "--log-dir", folder, "--sim-wire", first);
        var b = await CliHarness.RunAsync("engrave", QrCode, "--width-mm", "2", "--simulate", "--log-dir", folder, "--sim-wire", second);

        Assert.True(a.Exit == 0, a.Err);
        Assert.True(b.Exit == 0, b.Err);
        var lines = await File.ReadAllLinesAsync(first, TestContext.Current.CancellationToken);
        Assert.Equal("{\"wire\":1}", lines[0]);
        Assert.StartsWith("{\"end\":", lines[^1], StringComparison.Ordinal);
        Assert.Contains(lines, l => l.Contains("\"p\":\"s\",\"d\":\"w\"", StringComparison.Ordinal));
        Assert.Contains(lines, l => l.Contains("\"p\":\"l\",\"d\":\"r\"", StringComparison.Ordinal));

        // The twin is deterministic: the same job and seed give the same bytes at the same virtual times.
        Assert.Equal(lines, await File.ReadAllLinesAsync(second, TestContext.Current.CancellationToken));
    }

    [Fact]
    public async Task Engrave_SimWireOnPortsOrExistingFile_Exit2OneLine()
    {
        var existing = Path.Combine(folder, "there.jsonl");
        await File.WriteAllTextAsync(existing, "x", TestContext.Current.CancellationToken);

        var ports = await CliHarness.RunAsync("engrave", QrCode, "--width-mm", "2", "--stage-port", "/dev/null", "--laser-port", "/dev/null", "--log-dir", folder, "--sim-wire", Path.Combine(folder, "new.jsonl"));
        var taken = await CliHarness.RunAsync("engrave", QrCode, "--width-mm", "2", "--simulate", "--log-dir", folder, "--sim-wire", existing);

        Assert.Equal((2, "laserengrave: --sim-wire works only with --simulate: on real ports the flight recorder writes wire_*.jsonl beside the log"), (ports.Exit, ports.Err.TrimEnd()));
        Assert.Equal((2, $"laserengrave: --sim-wire {existing}: the file exists; give a new one"), (taken.Exit, taken.Err.TrimEnd()));
        Assert.Equal("x", await File.ReadAllTextAsync(existing, TestContext.Current.CancellationToken));
    }

    public void Dispose() => Directory.Delete(folder, recursive: true);
}
