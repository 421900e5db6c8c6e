using System.CommandLine;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Scheduling;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Faults;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Cli.Commands;

/// <summary>`laserengrave simulator --stage-port PATH --laser-port PATH [--fault SPEC] [--sim-options FILE]`: the machine in software on two ports, on the wall clock.</summary>
/// <remarks>
/// Typically on ptys made by socat, whose other ends the host opens as if they were the real ports. Stays up until
/// Ctrl+C, printing one line per connection event; when a port goes away (socat stopped) it is reopened once it is back.
/// </remarks>
internal static class SimulatorCommand
{
    private static readonly TimeSpan ReopenInterval = TimeSpan.FromMilliseconds(500);

    public static Command Create() => Create(static (path, baudRate) => SerialPortLink.Open(path, baudRate));

    /// <param name="open">Opens a port path at a baud rate as the simulator's end of the link.</param>
    internal static Command Create(Func<string, int, ISerialLink> open)
    {
        var stagePort = new Option<string>("--stage-port")
        {
            Description = "Port the Zaber chain answers on, e.g. /tmp/le-stage (one end of `socat -d -d pty,raw,echo=0,link=/tmp/le-stage pty,raw,echo=0,link=/tmp/le-stage-host`)",
            Required = true,
        };
        var laserPort = new Option<string>("--laser-port")
        {
            Description = "Port the laser gate answers on, e.g. /tmp/le-laser",
            Required = true,
        };
        var simOptions = MachineOptions.SimOptionsOption();
        var simSeed = MachineOptions.SimSeedOption();
        var fault = new Option<string[]>("--fault")
        {
            Description = "Inject faults, e.g. drop-reply:stage:after=10,no-ack:gate:after=4 (kinds: drop-reply, corrupt, delay, error, silent, disconnect, no-ack; see docs/simulator.md)",
        };
        var profile = new Option<string?>("--profile")
        {
            Description = "Machine profile (JSON); default: two Zaber T-LA60A, device 1 = X, device 2 = Y",
        };
        var command = new Command("simulator", "Run two Zaber T-LA60A and the laser gate in software on two ports, until Ctrl+C")
        {
            stagePort, laserPort, fault, profile, simOptions, simSeed,
        };
        command.SetAction((result, ct) => RunAsync(
            open,
            result.GetRequiredValue(stagePort),
            result.GetRequiredValue(laserPort),
            MachineOptions.SimulatorOptions(result, simOptions, simSeed, string.Join(',', result.GetValue(fault) ?? [])),
            result.GetValue(profile),
            result.InvocationConfiguration.Output,
            ct));
        return command;
    }

    private static async Task<int> RunAsync(
        Func<string, int, ISerialLink> open, string stagePath, string laserPath, SimulatorOptions options, string? profilePath, TextWriter output, CancellationToken cancellationToken)
    {
        var profile = profilePath is null ? MachineProfile.Default : MachineProfile.Load(profilePath);
        var faults = FaultInjector.ParseRules(options.FaultSpec);

        // The simulator stands in for the devices' firmware, which never waits for the computer: it asks for the CPU
        // priority a run on real ports gets (its threads, started below, inherit it).
        using var priority = RunPriority.Raise();
        var stage = open(stagePath, profile.StageBaudRate);
        ISerialLink laser;
        try
        {
            laser = open(laserPath, profile.Gate.BaudRate);
        }
        catch
        {
            await stage.DisposeAsync().ConfigureAwait(false);
            throw;
        }

        var print = new Lock();
        void Print(string line)
        {
            lock (print)
            {
                output.WriteLine($"{TimeProvider.System.GetLocalNow():HH:mm:ss} {line}");
            }
        }

        if (profile.Z is { } z)
        {
            Print($"simulator: the chain has a focus axis, Z = device {z.DeviceNumber}");
        }

        await using var machine = SimulatedMachine.Attach(stage, laser, profile, options);
        machine.EventRaised += (_, e) => Print($"{e.Port}: {e.Message}");
        Print($"simulator: stage (X = device {profile.X.DeviceNumber}, Y = device {profile.Y.DeviceNumber}) on {stagePath}, laser gate on {laserPath}, "
            + $"on the wall clock (a host in another process lives in real time), priority {priority.Description}, seed {options.Seed}{(faults.Count > 0 ? $", faults {string.Join(',', faults)}" : string.Empty)}; Ctrl+C to stop");

        try
        {
            await Task.WhenAll(
                KeepServingAsync(SimulatedMachine.StagePort, stagePath, profile.StageBaudRate, () => machine.StageServed, machine.ServeStage),
                KeepServingAsync(SimulatedMachine.LaserPort, laserPath, profile.Gate.BaudRate, () => machine.LaserServed, machine.ServeLaser)).ConfigureAwait(false);
        }
        catch (OperationCanceledException) when (cancellationToken.IsCancellationRequested)
        {
            Print("simulator: stopped");
        }

        return CliRunner.Ok;

        // When a port goes away (socat stopped), wait for it to come back and serve it again; the devices keep their state.
        async Task KeepServingAsync(string port, string path, int baudRate, Func<Task> served, Action<ISerialLink> serve)
        {
            while (true)
            {
                await served().WaitAsync(cancellationToken).ConfigureAwait(false);
                var reported = false;
                while (true)
                {
                    await Task.Delay(ReopenInterval, cancellationToken).ConfigureAwait(false);
                    try
                    {
                        serve(open(path, baudRate));
                        Print($"{port}: reopened {path}");
                        break;
                    }
                    catch (Exception ex) when (ex is DeviceException or IOException or UnauthorizedAccessException)
                    {
                        if (!reported)
                        {
                            Print($"{port}: waiting for {path} to come back ({ex.Message})");
                            reported = true;
                        }
                    }
                }
            }
        }
    }
}
