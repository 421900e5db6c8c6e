using System.CommandLine;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Machines;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Faults;
using LaserEngrave.Wire.Serial;

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

    public Option<string?> SimOptions { get; } = SimOptionsOption();

    /// <summary>The person accepts a laser gate without a watchdog (a frequency-only profile); commands that fire refuse such a gate without it.</summary>
    public Option<bool> AcceptNoWatchdog { get; } = new("--accept-no-watchdog")
    {
        Description = "Fire with a laser gate that has no watchdog (a frequencyOnly profile): if this computer hangs while the laser fires, only the interlock or the key switch stops it",
    };

    public Option<int?> SimSeed { get; } = SimSeedOption();

    /// <summary>Hidden: the twin's wire traffic as a flight recording (tools/wire-capture.sh compares builds with it).</summary>
    public Option<string?> SimWire { get; } = new("--sim-wire")
    {
        Description = "With --simulate: record every byte on the simulated links to this new file (flight-recorder format)",
        Hidden = true,
    };

    public void AddTo(Command command)
    {
        command.Options.Add(Simulate);
        command.Options.Add(StagePort);
        command.Options.Add(LaserPort);
        command.Options.Add(Fault);
        command.Options.Add(SimOptions);
        command.Options.Add(SimSeed);
        command.Options.Add(SimWire);
        command.Options.Add(AcceptNoWatchdog);
    }

    /// <summary>
    /// Refuses to fire a gate without a watchdog unless `--accept-no-watchdog` says the person accepts what then protects
    /// the laser (exit 2, the sentence, before anything opens).
    /// </summary>
    public void RefuseUnacceptedNoWatchdog(ParseResult result, MachineProfile profile)
    {
        if (!profile.Gate.HasWatchdog && !result.GetValue(AcceptNoWatchdog))
        {
            throw new UsageException($"{LaserGateProfile.NoWatchdogSentence}; give --accept-no-watchdog to accept it");
        }
    }

    /// <summary>
    /// Whether the gate is expected to time its switch-ons (CAPS? listing AFTER) before any port opens: never a
    /// frequency-only gate; the twin's as its options say; a real counting gate is asked at preflight, which refuses then.
    /// </summary>
    public bool ExpectsScheduledSwitchOns(ParseResult result, MachineProfile profile) =>
        profile.Gate.CountsBursts && (!result.GetValue(Simulate) || SimulatorOptionsFor(result).GateScheduledBursts);

    internal static Option<string?> SimOptionsOption() => new("--sim-options")
    {
        Description = "With the simulator: a JSON file of simulator options (latency model, seed, faults; see docs/simulator.md)",
    };

    internal static Option<int?> SimSeedOption() => new("--sim-seed")
    {
        Description = "With the simulator: the seed of its random draws (latency jitter); the same seed repeats a run exactly (default 1)",
    };

    /// <summary>
    /// The simulator options the command line gives: the front ends' twin (a realistically late host), the options file
    /// over it, then the seed and the faults over that.
    /// </summary>
    internal static SimulatorOptions SimulatorOptions(ParseResult result, Option<string?> file, Option<int?> seed, string faultSpec)
    {
        var options = LaserEngrave.Simulator.SimulatorOptions.FrontEnd;
        if (result.GetValue(file) is { } path)
        {
            options = SimulatorOptionsFile.Load(path, options);
        }

        if (result.GetValue(seed) is { } s)
        {
            options = options with { Seed = s };
        }

        return faultSpec.Length > 0 ? options with { FaultSpec = faultSpec } : options;
    }

    /// <summary>The simulator options of a simulated machine (for the run log: the seed).</summary>
    public SimulatorOptions SimulatorOptionsFor(ParseResult result) => SimulatorOptions(result, SimOptions, SimSeed, FaultSpec(result));

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

        if (!simulate && result.GetValue(SimWire) is not null)
        {
            throw new UsageException("--sim-wire works only with --simulate: on real ports the flight recorder writes wire_*.jsonl beside the log");
        }

        if (simulate && result.GetValue(SimWire) is { } wire && (File.Exists(wire) || Directory.Exists(wire)))
        {
            throw new UsageException($"--sim-wire {wire}: the file exists; give a new one");
        }

        if (!simulate && (result.GetValue(SimOptions) is not null || result.GetValue(SimSeed) is not null))
        {
            throw new UsageException("--sim-options and --sim-seed work only with --simulate");
        }

        if (simulate)
        {
            // Read here so that a bad file is refused before anything is created or opened.
            SimulatorOptionsFor(result);
        }

        // Parsed here only to refuse a bad spec before anything is created or opened.
        FaultInjector.ParseRules(FaultSpec(result));
    }

    public string FaultSpec(ParseResult result) => string.Join(',', result.GetValue(Fault) ?? []);

    /// <summary>Called, on the async flow that set it, just before a machine (ports or simulator) is opened.</summary>
    /// <remarks>The seam through which tests prove that bad input is refused before anything opens, so nothing can move.</remarks>
    internal static AsyncLocal<Action?> Opening { get; } = new();

    /// <summary>Opens the machine the options name through the one <see cref="MachineFactory"/>; the caller disposes it (devices first, then the simulator).</summary>
    /// <param name="result">The parsed options.</param>
    /// <param name="profile">The machine.</param>
    /// <param name="recorder">On real ports, the flight recorder the links write through; the simulator records only to --sim-wire.</param>
    public OpenMachine Open(ParseResult result, MachineProfile profile, WireRecorder? recorder = null)
    {
        Validate(result);
        Opening.Value?.Invoke();
        return result.GetValue(Simulate)
            ? MachineFactory.OpenTwin(profile, SimulatorOptionsFor(result), result.GetValue(SimWire))
            : MachineFactory.OpenPorts(result.GetValue(StagePort)!, result.GetValue(LaserPort)!, profile, recorder);
    }
}
