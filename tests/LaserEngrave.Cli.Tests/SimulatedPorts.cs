using LaserEngrave.Testing;

namespace LaserEngrave.Cli.Tests;

/// <summary>Two socat pty pairs with `laserengrave simulator` on one end of each: the other ends are the ports a command opens.</summary>
/// <remarks>The simulator runs in a process of its own, as it does in use; sharing the test's thread pool would make its virtual clock stall.</remarks>
internal sealed class SimulatedPorts : IAsyncDisposable
{
    private SocatPtyPair? _stage;
    private SocatPtyPair? _laser;
    private SimulatorProcess? _simulator;

    /// <summary>The stage's port, for `--port` or `--stage-port`.</summary>
    public string StagePort => _stage!.B;

    /// <summary>The laser gate's port, for `--port` or `--laser-port`.</summary>
    public string LaserPort => _laser!.B;

    /// <summary>The stage pty's end the simulator holds (for the port-in-use test).</summary>
    public string SimulatorStagePort => _stage!.A;

    public static async Task<SimulatedPorts> StartAsync(CancellationToken cancellationToken)
    {
        var ports = new SimulatedPorts();
        try
        {
            ports._stage = await SocatPtyPair.StartAsync(cancellationToken);
            ports._laser = await SocatPtyPair.StartAsync(cancellationToken);
            ports._simulator = await SimulatorProcess.StartAsync(ports._stage, ports._laser, cancellationToken);
            return ports;
        }
        catch
        {
            await ports.DisposeAsync();
            throw;
        }
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
    }
}
