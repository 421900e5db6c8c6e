using System.Text.Json;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Cli.Tests;

/// <summary>`machine latency` on the in-process simulator (virtual time, so the figures are the same for the same seed).</summary>
public class MachineCommandTests
{
    [Fact]
    public async Task MachineLatencySimulate_Json_MeasuresTheSimulatorsDefaults()
    {
        var (exit, output, error) = await CliHarness.RunAsync("machine", "latency", "--simulate", "--json");

        Assert.True(exit == 0, error);
        using var json = JsonDocument.Parse(output);
        var latency = json.RootElement.GetProperty("latency");
        Assert.Equal(1.0, latency.GetProperty("stageMs").GetDouble(), 0.05);
        Assert.Equal(0.5, latency.GetProperty("stageJitterMs").GetDouble(), 0.05);
        Assert.Equal(1.0, latency.GetProperty("gateMs").GetDouble(), 0.05);
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

            // The gate's 0.5 ms processing against the 0.4 ms kept: the 0.1 ms left over shows up as adapter latency, half each way.
            Assert.Equal(1.05, saved.Latency.GateMs, 0.1);
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
