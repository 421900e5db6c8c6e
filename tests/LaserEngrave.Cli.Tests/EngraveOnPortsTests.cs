using System.Text.Json;
using LaserEngrave.Core.Logging;
using LaserEngrave.Testing;

namespace LaserEngrave.Cli.Tests;

/// <summary>`engrave` and the test moves on real ports: socat ptys with `laserengrave simulator` on the other ends.</summary>
/// <remarks>The simulator runs in a process of its own, as it does in use; sharing the test's thread pool would make its virtual clock stall.</remarks>
public sealed class EngraveOnPortsTests : IAsyncLifetime
{
    private readonly string _logDir = Path.Combine(Path.GetTempPath(), $"le-cli-ports-{Guid.NewGuid():N}");
    private SocatPtyPair? _stage;
    private SocatPtyPair? _laser;
    private SimulatorProcess? _simulator;

    private string StagePort => _stage!.B;

    private string LaserPort => _laser!.B;

    public async ValueTask InitializeAsync()
    {
        var ct = TestContext.Current.CancellationToken;
        _stage = await SocatPtyPair.StartAsync(ct);
        _laser = await SocatPtyPair.StartAsync(ct);
        _simulator = await SimulatorProcess.StartAsync(_stage, _laser, ct);
    }

    public async ValueTask DisposeAsync()
    {
        if (_simulator is not null)
        {
            await _simulator.DisposeAsync();
        }

        if (_stage is not null)
        {
            await _stage.DisposeAsync();
        }

        if (_laser is not null)
        {
            await _laser.DisposeAsync();
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
