using LaserEngrave.Devices.LaserGate;
using LaserEngrave.Devices.Zaber;
using LaserEngrave.Simulator;

namespace LaserEngrave.Cli.Commands;

/// <summary>An open machine: the stage, the gate, the clock they run on and, when simulated, the simulator behind them.</summary>
internal sealed class MachineSession(ZaberChain stage, PicLaserGate gate, TimeProvider timeProvider, string stagePort, string laserPort, SimulatedMachine? simulator)
    : IAsyncDisposable
{
    public ZaberChain Stage { get; } = stage;

    public PicLaserGate Gate { get; } = gate;

    public TimeProvider TimeProvider { get; } = timeProvider;

    public string StagePort { get; } = stagePort;

    public string LaserPort { get; } = laserPort;

    /// <summary>The in-process simulator, or null on real ports.</summary>
    public SimulatedMachine? Simulator { get; } = simulator;

    public async ValueTask DisposeAsync()
    {
        await Gate.DisposeAsync().ConfigureAwait(false);
        await Stage.DisposeAsync().ConfigureAwait(false);
        if (Simulator is not null)
        {
            await Simulator.DisposeAsync().ConfigureAwait(false);
        }
    }
}
