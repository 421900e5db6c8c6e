using LaserEngrave.Core.Geometry;
using LaserEngrave.Testing;

namespace LaserEngrave.Cli.Tests;

/// <summary>The wiring-check commands through real ptys (socat) with `laserengrave simulator` on the other ends, as a technician would use them.</summary>
public sealed class DeviceCommandsTests : IAsyncLifetime
{
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
    }

    [Fact(Timeout = 60_000)]
    public async Task StageIdentify_SimulatedChain_ListsBothAxesWithFirmware()
    {
        var (exit, output, error) = await CliHarness.RunAsync("stage", "--port", StagePort, "identify");

        Assert.True(exit == 0, error);
        Assert.Contains("2 Zaber device(s)", output, StringComparison.Ordinal);
        Assert.Contains("device 1", output, StringComparison.Ordinal);
        Assert.Contains("device 2", output, StringComparison.Ordinal);
        Assert.Contains("firmware 5.23", output, StringComparison.Ordinal);
    }

    [Fact(Timeout = 60_000)]
    public async Task StageHomeThenMoveAbs_PositionIsTheTargetRoundedOnce()
    {
        var home = await CliHarness.RunAsync("stage", "--port", StagePort, "home");
        var (exit, _, error) = await CliHarness.RunAsync("stage", "--port", StagePort, "move-abs", "1000", "2500.5");
        var (_, position, _) = await CliHarness.RunAsync("stage", "--port", StagePort, "position");

        Assert.True(home.Exit == 0, home.Err);
        Assert.Contains("X: 0.000 µm (0 microsteps)", home.Out, StringComparison.Ordinal);
        Assert.True(exit == 0, error);
        var um = MachineProfile.Default.X.MicrostepUm;
        var x = (long)Math.Round(1000 / um, MidpointRounding.AwayFromZero);
        var y = (long)Math.Round(2500.5 / um, MidpointRounding.AwayFromZero);
        Assert.Contains($"X: {x * um:0.000} µm ({x} microsteps)", position, StringComparison.Ordinal);
        Assert.Contains($"Y: {y * um:0.000} µm ({y} microsteps)", position, StringComparison.Ordinal);
    }

    [Fact(Timeout = 60_000)]
    public async Task StageMoveAbs_OutsideTravel_Exit2AndNothingMoves()
    {
        var (_, before, _) = await CliHarness.RunAsync("stage", "--port", StagePort, "position");

        var (exit, _, error) = await CliHarness.RunAsync("stage", "--port", StagePort, "move-abs", "70000", "0");
        var (_, after, _) = await CliHarness.RunAsync("stage", "--port", StagePort, "position");

        Assert.Equal(2, exit);
        Assert.Contains("outside the travel", error, StringComparison.Ordinal);
        Assert.Equal(before, after);
    }

    [Fact(Timeout = 60_000)]
    public async Task LaserCommands_IdentifyOnStatusOff_GateFollows()
    {
        var (identifyExit, identify, _) = await CliHarness.RunAsync("laser", "--port", LaserPort, "identify");
        var (onExit, _, onError) = await CliHarness.RunAsync("laser", "--port", LaserPort, "on", "1000", "--seconds", "0.3");
        var (statusExit, status, _) = await CliHarness.RunAsync("laser", "--port", LaserPort, "status");

        Assert.Equal(0, identifyExit);
        Assert.Contains("PICGATE", identify, StringComparison.Ordinal);
        Assert.True(onExit == 0, onError);
        Assert.Equal(0, statusExit);
        Assert.Contains("not firing", status, StringComparison.Ordinal);
    }

    [Fact(Timeout = 60_000)]
    public async Task MachineLatency_OnPtys_MeasuresBothDevicesAndWritesTheProfile()
    {
        var path = CliHarness.TempFile(".json");
        try
        {
            // On the wall clock: only what was measured and written is checked, not how long it took.
            var (exit, output, error) = await CliHarness.RunAsync("machine", "latency", "--stage-port", StagePort, "--laser-port", LaserPort, "--count", "10", "--profile", path, "--write");

            Assert.True(exit == 0, error);
            Assert.Contains("device 1 (X): 10 round trips", output, StringComparison.Ordinal);
            Assert.Contains("device 2 (Y): 10 round trips", output, StringComparison.Ordinal);
            Assert.Contains($"laser gate on {LaserPort}: 10 round trips", output, StringComparison.Ordinal);
            var saved = MachineProfile.Load(path);
            Assert.Equal(MachineProfile.Default.Latency.GateProcessingMs, saved.Latency.GateProcessingMs);
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact(Timeout = 60_000)]
    public async Task Stage_MissingPort_Exit1NamingThePort()
    {
        var (exit, _, error) = await CliHarness.RunAsync("stage", "--port", "/dev/ttyNOPE42", "identify");

        Assert.Equal(1, exit);
        Assert.Contains("/dev/ttyNOPE42", error, StringComparison.Ordinal);
        Assert.Contains("no such port", error, StringComparison.Ordinal);
        Assert.Single(error.TrimEnd().Split('\n'));
    }

    [Fact(Timeout = 60_000)]
    public async Task Stage_PortHeldByTheSimulator_Exit1SaysInUse()
    {
        // The simulator process holds the A end; opening it again from here must be refused, not share the line.
        var (exit, _, error) = await CliHarness.RunAsync("stage", "--port", _ports!.SimulatorStagePort, "identify");

        Assert.Equal(1, exit);
        Assert.Equal($"laserengrave: {_ports.SimulatorStagePort}: port is in use by another program", error.TrimEnd());
    }

    [Fact(Timeout = 60_000)]
    public async Task Ports_Lists_WithoutFailing()
    {
        var (exit, _, error) = await CliHarness.RunAsync("ports");

        Assert.True(exit == 0, error);
    }
}

/// <summary>`laserengrave simulator` on its own ptys, spoken to by `laserengrave stage` and `laser` on the other ends.</summary>
public sealed class SimulatorCommandTests
{
    [Fact(Timeout = 60_000)]
    public async Task Simulator_OnPtys_AnswersTheWiringChecksUntilCancelled()
    {
        var ct = TestContext.Current.CancellationToken;
        await using var stage = await SocatPtyPair.StartAsync(ct);
        await using var laser = await SocatPtyPair.StartAsync(ct);
        using var stop = CancellationTokenSource.CreateLinkedTokenSource(ct);
        using var simOut = new StringWriter();
        using var simErr = new StringWriter();
        var simulator = CliRunner.InvokeAsync(Program.BuildRoot(), ["simulator", "--stage-port", stage.A, "--laser-port", laser.A], simOut, simErr, stop.Token);

        var (stageExit, stageOut, stageErr) = await RetryUntilReadyAsync(() => CliHarness.RunAsync("stage", "--port", stage.B, "identify"));
        var (laserExit, laserOut, _) = await CliHarness.RunAsync("laser", "--port", laser.B, "identify");
        await stop.CancelAsync();
        var simulatorExit = await simulator.WaitAsync(TimeSpan.FromSeconds(20), ct);

        Assert.True(stageExit == 0, stageErr);
        Assert.Contains("2 Zaber device(s)", stageOut, StringComparison.Ordinal);
        Assert.Equal(0, laserExit);
        Assert.Contains("PICGATE", laserOut, StringComparison.Ordinal);
        Assert.True(simulatorExit is 0 or 1, simErr.ToString());
    }

    [Fact(Timeout = 30_000)]
    public async Task Simulator_BadFaultSpec_Exit2NamingTheRule()
    {
        var ct = TestContext.Current.CancellationToken;
        await using var stage = await SocatPtyPair.StartAsync(ct);
        await using var laser = await SocatPtyPair.StartAsync(ct);

        var (exit, _, error) = await CliHarness.RunAsync("simulator", "--stage-port", stage.A, "--laser-port", laser.A, "--fault", "explode:stage");

        Assert.Equal(2, exit);
        Assert.Contains("explode", error, StringComparison.Ordinal);
    }

    // The simulator opens its ports a moment after it starts; the first identify may find nobody answering yet.
    private static async Task<(int Exit, string Out, string Err)> RetryUntilReadyAsync(Func<Task<(int Exit, string Out, string Err)>> run)
    {
        (int Exit, string Out, string Err) last = default;
        for (var attempt = 0; attempt < 5; attempt++)
        {
            last = await run();
            if (last.Exit == 0)
            {
                return last;
            }

            await Task.Delay(200, TestContext.Current.CancellationToken);
        }

        return last;
    }
}
