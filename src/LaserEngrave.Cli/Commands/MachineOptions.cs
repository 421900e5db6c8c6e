using System.CommandLine;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Machine;
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

    /// <summary>Called, on the async flow that set it, just before a machine (ports or simulator) is opened.</summary>
    /// <remarks>The seam through which tests prove that bad input is refused before anything opens, so nothing can move.</remarks>
    internal static AsyncLocal<Action?> Opening { get; } = new();

    /// <summary>Opens the machine the options name; the caller disposes it (devices first, then the simulator).</summary>
    public MachineSession Open(ParseResult result, MachineProfile profile)
    {
        Validate(result);
        Opening.Value?.Invoke();
        return result.GetValue(Simulate)
            ? SimulatedMachine.OpenInProcess(profile, new SimulatorOptions { FaultSpec = FaultSpec(result) })
            : MachineSession.OpenPorts(result.GetValue(StagePort)!, result.GetValue(LaserPort)!, profile);
    }
}
