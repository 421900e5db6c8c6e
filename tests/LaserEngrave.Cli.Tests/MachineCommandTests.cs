using System.Text.Json;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator.LaserGate;

namespace LaserEngrave.Cli.Tests;

/// <summary>`machine latency` on the in-process simulator (virtual time, so the figures are the same for the same seed).</summary>
public class MachineCommandTests
{
    /// <summary>The twin's gate's time for "PING\n" (5 bytes), as the reference firmware's (GateFirmwareTiming), ms.</summary>
    private static readonly double PingMs = (GateFirmwareTiming.StopBaseCyclesFrequency + (5 * GateFirmwareTiming.CyclesPerLineByte)) / GateFirmwareTiming.ClockHz * 1000;

    [Fact]
    public async Task MachineLatencySimulate_Json_MeasuresTheSimulatorsDefaults()
    {
        // The front ends' twin reads a reply in 2,000 up to 60 ms late (a loaded computer), which a measurement takes for
        // the adapter's spread: the defaults are measured on a computer that wakes late but never reads late or stalls.
        var options = Path.Combine(Path.GetTempPath(), $"le-cli-latency-{Guid.NewGuid():N}.json");
        await File.WriteAllTextAsync(options, """{ "hostLateness": { "typicalMs": 0.5, "tailProbability": 0.01, "tailMs": 5 } }""", TestContext.Current.CancellationToken);
        var (exit, output, error) = await CliHarness.RunAsync("machine", "latency", "--simulate", "--sim-options", options, "--json");
        File.Delete(options);

        Assert.True(exit == 0, error);
        using var json = JsonDocument.Parse(output);
        var latency = json.RootElement.GetProperty("latency");
        Assert.Equal(1.0, latency.GetProperty("stageMs").GetDouble(), 0.05);
        Assert.Equal(0.5, latency.GetProperty("stageJitterMs").GetDouble(), 0.05);
        // The twin's gate answers PING in the reference firmware's 0.055 ms where the default profile keeps 0.19 ms (a
        // BURST's): the measurement takes the difference for the adapter's, half of it each way.
        Assert.Equal(1.0 + ((PingMs - 0.19) / 2), latency.GetProperty("gateMs").GetDouble(), 0.05);
        Assert.Equal(0.5, latency.GetProperty("gateJitterMs").GetDouble(), 0.05);
        Assert.Equal(200, json.RootElement.GetProperty("x").GetProperty("count").GetInt32());
        Assert.Equal(400, json.RootElement.GetProperty("stage").GetProperty("count").GetInt32());
        Assert.False(json.RootElement.GetProperty("written").GetBoolean());
    }

    [Fact]
    public async Task MachineLatencySimulate_SameSeed_SameOutput()
    {
        var first = await CliHarness.RunAsync("machine", "latency", "--simulate", "--sim-seed", "9", "--count", "30");
        var again = await CliHarness.RunAsync("machine", "latency", "--simulate", "--sim-seed", "9", "--count", "30");

        Assert.Equal(0, first.Exit);
        Assert.Equal(first.Out, again.Out);
        Assert.Contains("device 1 (X): 30 round trips, min ", first.Out, StringComparison.Ordinal);
        Assert.Contains("kept from the profile", first.Out, StringComparison.Ordinal);
    }

    [Fact]
    public async Task MachineLatencyWrite_ExistingProfile_OnlyItsLatencySectionChanges()
    {
        var path = CliHarness.TempFile(".json");
        try
        {
            var lab = MachineProfile.Default with { Name = "Lab 2", Latency = new LatencyProfile { StageMs = 7, GateProcessingMs = 0.4, GateProcessingJitterMs = 0.1 } };
            lab.Save(path);

            var (exit, output, error) = await CliHarness.RunAsync("machine", "latency", "--simulate", "--count", "100", "--profile", path, "--write");

            Assert.True(exit == 0, error);
            Assert.Contains($"Written:          the latency section of {path}", output, StringComparison.Ordinal);
            var saved = MachineProfile.Load(path);
            Assert.Equal("Lab 2", saved.Name);
            Assert.Equal(lab.Gate, saved.Gate);
            Assert.Equal(1.0, saved.Latency.StageMs, 0.1);
            Assert.Equal(0.4, saved.Latency.GateProcessingMs);
            Assert.Equal(0.1, saved.Latency.GateProcessingJitterMs);

            // The gate's processing of PING (the reference firmware's 0.055 ms) against the 0.4 ms kept: the difference shows
            // up as adapter latency, half each way.
            Assert.Equal(1.0 + ((PingMs - 0.4) / 2), saved.Latency.GateMs, 0.1);
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public async Task MachineLatencyWrite_MissingProfile_CreatedFromTheDefault()
    {
        var path = CliHarness.TempFile(".json");
        try
        {
            var (exit, _, error) = await CliHarness.RunAsync("machine", "latency", "--simulate", "--count", "20", "--profile", path, "--write");

            Assert.True(exit == 0, error);
            var saved = MachineProfile.Load(path);
            Assert.Equal(MachineProfile.Default.Name, saved.Name);
            Assert.InRange(saved.Latency.StageMs, 0.5, 1.5);
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public async Task MachineLatency_MissingProfileWithoutWrite_Exit2()
    {
        var (exit, _, error) = await CliHarness.RunAsync("machine", "latency", "--simulate", "--profile", CliHarness.TempFile(".json"));

        Assert.Equal(2, exit);
        Assert.StartsWith("laserengrave: ", error, StringComparison.Ordinal);
    }
}

/// <summary>`machine check` against `laserengrave simulator` on socat ptys: the first day on a machine, through the real serial path.</summary>
public sealed class MachineCheckOnPortsTests : IAsyncLifetime
{
    private SimulatedPorts? _ports;

    public async ValueTask InitializeAsync() => _ports = await SimulatedPorts.StartAsync(TestContext.Current.CancellationToken);

    public async ValueTask DisposeAsync()
    {
        if (_ports is not null)
        {
            await _ports.DisposeAsync();
        }
    }

    [Fact(Timeout = 120_000)]
    public async Task MachineCheckOnPorts_Yes_EveryStepPassesAndTheReportAndProfileAreWritten()
    {
        var profile = CliHarness.TempFile(".json");
        var report = CliHarness.TempFile(".txt");
        try
        {
            var (exit, output, error) = await CliHarness.RunAsync(
                "machine", "check", "--stage-port", _ports!.StagePort, "--laser-port", _ports.LaserPort, "--yes", "--count", "10", "--distance-mm", "0.5",
                "--profile", profile, "--write", "--report", report, "--json");

            using var json = JsonDocument.Parse(output);
            var steps = json.RootElement.GetProperty("steps").EnumerateArray().Select(s => (s.GetProperty("name").GetString(), s.GetProperty("result").GetString(), s.GetProperty("finding").GetString())).ToList();
            Assert.Equal(["laser gate", "X axis", "Y axis", "homing", "X move", "Y move", "latencies", "gate watchdog"], steps.Select(s => s.Item1));
            Assert.All(steps.Where(s => s.Item1 != "latencies"), s => Assert.True(s.Item2 == "passed", $"{s.Item1}: {s.Item3}"));
            Assert.Contains("firmware 5.23", File.ReadAllText(report), StringComparison.Ordinal);
            Assert.Contains("watchdog tripped", File.ReadAllText(report), StringComparison.Ordinal);
            var latency = steps.Single(s => s.Item1 == "latencies");
            if (latency.Item2 == "passed")
            {
                // Timing on the wall clock: a test machine busy enough gives round trips no profile may hold, and then nothing is written.
                Assert.True(exit == 0, $"{error}\n{output}");
                Assert.InRange(MachineProfile.Load(profile).Latency.StageMs, 0, 100);
            }
            else
            {
                Assert.Equal(1, exit);
                Assert.Contains("free this computer of other work", latency.Item3, StringComparison.Ordinal);
                Assert.False(File.Exists(profile) && new FileInfo(profile).Length > 0, "a profile was written from latencies it cannot hold");
            }
        }
        finally
        {
            File.Delete(profile);
            File.Delete(report);
        }
    }
}

/// <summary>`machine check` on the in-process simulator.</summary>
public class MachineCheckSimulateTests
{
    [Fact]
    public async Task MachineCheckSimulate_NoConfirmation_WatchdogSkippedAndNotPassed()
    {
        var (exit, output, _) = await CliHarness.RunAsync("machine", "check", "--simulate", "--count", "10", "--distance-mm", "1");

        Assert.Equal(1, exit);
        Assert.Contains("skip   gate watchdog: not tripped", output, StringComparison.Ordinal);
        Assert.Contains("ok     X move: device 1 (X) sent to 10079 microsteps", output, StringComparison.Ordinal);
    }

    [Fact]
    public async Task MachineCheckSimulate_Firmware506_SaysItHomesAtTheTargetSpeed()
    {
        var options = CliHarness.TempFile(".json");
        try
        {
            File.WriteAllText(options, """{ "firmwareVersion": 506 }""");
            var (exit, output, error) = await CliHarness.RunAsync("machine", "check", "--simulate", "--yes", "--count", "10", "--distance-mm", "1", "--sim-options", options);

            Assert.True(exit == 0, $"{error}\n{output}");
            Assert.Contains("firmware 5.06 (homes at the Target Speed (no Set Home Speed before 5.20))", output, StringComparison.Ordinal);
            Assert.Contains("Result: every step passed", output, StringComparison.Ordinal);
        }
        finally
        {
            File.Delete(options);
        }
    }

    [Fact]
    public async Task MachineCheckSimulate_RoundTripsNoProfileCanHold_LatencyFailsAndNothingIsWritten()
    {
        var options = CliHarness.TempFile(".json");
        var profile = CliHarness.TempFile(".json");
        try
        {
            File.WriteAllText(options, """{ "adapterLatency": { "meanMs": 110, "spreadMs": 20 } }""");
            var (exit, output, _) = await CliHarness.RunAsync("machine", "check", "--simulate", "--yes", "--count", "10", "--distance-mm", "1", "--sim-options", options, "--profile", profile, "--write");

            Assert.Equal(1, exit);
            Assert.Contains("FAILED latencies: round trips up to", output, StringComparison.Ordinal);
            Assert.Contains("Not written", output, StringComparison.Ordinal);
            Assert.False(File.Exists(profile));
        }
        finally
        {
            File.Delete(options);
            File.Delete(profile);
        }
    }

    [Theory]
    [InlineData("0")]
    [InlineData("NaN")]
    [InlineData("61")]
    public async Task MachineCheck_DistanceOutOfRange_Exit2NothingOpened(string mm)
    {
        var (exit, _, error) = await CliHarness.RunAsync("machine", "check", "--simulate", "--distance-mm", mm);

        Assert.Equal(2, exit);
        Assert.Contains("--distance-mm", error, StringComparison.Ordinal);
    }
}
