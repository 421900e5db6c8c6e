using System.Text.Json;
using LaserEngrave.Core.Logging;

namespace LaserEngrave.Cli.Tests;

/// <summary>`engrave` and the test moves on real ports: socat ptys with `laserengrave simulator` on the other ends.</summary>
public sealed class EngraveOnPortsTests : IAsyncLifetime
{
    private readonly string _logDir = Path.Combine(Path.GetTempPath(), $"le-cli-ports-{Guid.NewGuid():N}");
    private SimulatedPorts? _ports;

    private string StagePort => _ports!.StagePort;

    private string LaserPort => _ports!.LaserPort;

    public async ValueTask InitializeAsync()
    {
        _ports = await SimulatedPorts.StartAsync(TestContext.Current.CancellationToken);
    }

    public async ValueTask DisposeAsync()
    {
        if (_ports is not null)
        {
            await _ports.DisposeAsync();
        }

        if (Directory.Exists(_logDir))
        {
            Directory.Delete(_logDir, recursive: true);
        }
    }

    [Fact(Timeout = 120_000)]
    public async Task EngraveOnPorts_SmallImage_CompletesAndLogsThePortsAndFirmware()
    {
        // Small: on ports the simulator runs on the wall clock, so a job takes its real time.
        Directory.CreateDirectory(_logDir);
        var image = Path.Combine(_logDir, "small.pbm");
        await File.WriteAllTextAsync(image, "P1\n6 3\n1 1 0 0 1 1\n0 1 1 1 1 0\n1 0 1 0 1 0\n", TestContext.Current.CancellationToken);

        // The serial path, step by step (paper): on a loaded test machine the wall-clock simulator can shift by more than
        // any latency model, and timed switching is proven in virtual time.
        var (exit, output, error) = await CliHarness.RunAsync(
            "engrave", image, "--width-mm", "0.6", "--origin-mm", "1,1", "--strategy", "paper", "--stage-port", StagePort, "--laser-port", LaserPort, "--json", "--log-dir", _logDir);

        Assert.True(exit == 0, error);
        using var json = JsonDocument.Parse(output);
        Assert.Equal("completed", json.RootElement.GetProperty("outcome").GetString());
        Assert.False(json.RootElement.GetProperty("simulated").GetBoolean());
        Assert.Equal(JsonValueKind.Null, json.RootElement.GetProperty("missingPixels").ValueKind);
        var record = RunLogStore.Read(json.RootElement.GetProperty("logPath").GetString()!);
        Assert.Equal(record.RunsTotal, record.RunsDone);
        Assert.Equal([StagePort, StagePort, LaserPort], record.Devices.Select(d => d.Port));
        Assert.Equal("5.23", record.Devices[0].Firmware);
    }

    [Fact(Timeout = 60_000)]
    public async Task GotoOnPorts_Position_ArrivesWithTheLaserOff()
    {
        var (exit, output, error) = await CliHarness.RunAsync("goto", "3", "2", "--stage-port", StagePort, "--laser-port", LaserPort);

        Assert.True(exit == 0, error);
        Assert.EndsWith("= 3, 2 mm; laser off", output.TrimEnd(), StringComparison.Ordinal);
    }
}
