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
    public async Task EngraveOnPorts_QrCode_CompletesAndLogsThePortsAndFirmware()
    {
        var image = Path.Combine(CliHarness.RepositoryRoot, "assets", "qr-code.bmp");

        var (exit, output, error) = await CliHarness.RunAsync(
            "engrave", image, "--width-mm", "2", "--origin-mm", "1,1", "--stage-port", StagePort, "--laser-port", LaserPort, "--json", "--log-dir", _logDir);

        Assert.True(exit == 0, error);
        using var json = JsonDocument.Parse(output);
        Assert.Equal("completed", json.RootElement.GetProperty("outcome").GetString());
        Assert.False(json.RootElement.GetProperty("simulated").GetBoolean());
        Assert.Equal(JsonValueKind.Null, json.RootElement.GetProperty("missingPixels").ValueKind);
        var record = RunLogStore.Read(json.RootElement.GetProperty("logPath").GetString()!);
        Assert.Equal(record.RunsTotal, record.RunsDone);
        Assert.Equal([StagePort, StagePort, LaserPort], record.Devices.Select(d => d.Port));
        Assert.Equal("5.02", record.Devices[0].Firmware);
    }

    [Fact(Timeout = 60_000)]
    public async Task GotoOnPorts_Position_ArrivesWithTheLaserOff()
    {
        var (exit, output, error) = await CliHarness.RunAsync("goto", "2", "3", "--stage-port", StagePort, "--laser-port", LaserPort);

        Assert.True(exit == 0, error);
        Assert.EndsWith("= 2, 3 mm; laser off", output.TrimEnd(), StringComparison.Ordinal);
    }
}
