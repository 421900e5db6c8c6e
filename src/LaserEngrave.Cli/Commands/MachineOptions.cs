using System.CommandLine;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.LaserGate;
using LaserEngrave.Devices.Zaber;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Faults;

namespace LaserEngrave.Cli.Commands;

/// <summary>Which machine a run or a test move uses: the built-in simulator (`--simulate`) or two serial ports.</summary>
internal sealed class MachineOptions
{
    public Option<bool> Simulate { get; } = new("--simulate")
    {
        Description = "Run on the built-in simulator, in virtual time (no hardware)",
    };

    public Option<string?> StagePort { get; } = new("--stage-port")
    {
        Description = "Serial port of the Zaber chain, e.g. COM3 or /dev/ttyUSB0",
    };

    public Option<string?> LaserPort { get; } = new("--laser-port")
    {
        Description = "Serial port of the laser gate, e.g. COM4 or /dev/ttyUSB1",
    };

    public Option<string[]> Fault { get; } = new("--fault")
    {
        Description = "With --simulate: inject faults, e.g. silent:stage:after=200 or no-ack:gate:after=30 (see docs/simulator.md)",
    };

    public void AddTo(Command command)
    {
        command.Options.Add(Simulate);
        command.Options.Add(StagePort);
        command.Options.Add(LaserPort);
        command.Options.Add(Fault);
    }

    /// <summary>Checks the options agree (one machine, both ports, faults only on the simulator) before anything opens.</summary>
    public void Validate(ParseResult result)
    {
        var simulate = result.GetValue(Simulate);
        var stage = result.GetValue(StagePort);
        var laser = result.GetValue(LaserPort);
        if (simulate && (stage is not null || laser is not null))
        {
            throw new UsageException("--simulate and --stage-port/--laser-port contradict each other: give one machine");
        }

        if (!simulate && (stage is null || laser is null))
        {
            throw new UsageException(stage is null && laser is null
                ? "give the machine: --simulate, or --stage-port P --laser-port Q"
                : $"give both ports: {(stage is null ? "--stage-port" : "--laser-port")} is missing");
        }

        if (!simulate && FaultSpec(result).Length > 0)
        {
            throw new UsageException("--fault works only with --simulate");
        }

        // Parsed here only to refuse a bad spec before anything is created or opened.
        FaultInjector.ParseRules(FaultSpec(result));
    }

    public string FaultSpec(ParseResult result) => string.Join(',', result.GetValue(Fault) ?? []);

    /// <summary>Opens the machine the options name; the caller disposes it (devices first, then the simulator).</summary>
    public MachineSession Open(ParseResult result, MachineProfile profile)
    {
        Validate(result);
        if (result.GetValue(Simulate))
        {
            var simulator = SimulatedMachine.CreateInProcess(profile, new SimulatorOptions { FaultSpec = FaultSpec(result) });
            var chain = new ZaberChain(new ZaberConnection(simulator.StageLink, simulator.TimeProvider), profile);
            var gate = new PicLaserGate(simulator.LaserLink, profile.Gate, simulator.TimeProvider);
            return new MachineSession(chain, gate, simulator.TimeProvider, "simulator", "simulator", simulator);
        }

        var stagePort = result.GetValue(StagePort)!;
        var laserPort = result.GetValue(LaserPort)!;
        var stage = ZaberChain.Open(stagePort, profile);
        try
        {
            return new MachineSession(stage, PicLaserGate.Open(laserPort, profile.Gate), TimeProvider.System, stagePort, laserPort, null);
        }
        catch
        {
            stage.DisposeAsync().AsTask().GetAwaiter().GetResult();
            throw;
        }
    }
}
