using System.CommandLine;
using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Replay;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Cli.Commands;

/// <summary>`laserengrave replay LOG`: what a recorded run on real ports actually burned, by its recorded bytes and times through the twin.</summary>
/// <remarks>
/// The run's job comes from its log (the image checked against its SHA-256, as --from-log does), the bytes and times from
/// the flight recorder beside it; the devices are the twin's, the figures those of `engrave --simulate`. Exit 2 for a log
/// without a recording and a truncated, cut-off or corrupt recording.
/// </remarks>
internal static class ReplayCommand
{
    public static Command Create()
    {
        var log = new Argument<string>("LOG") { Description = "The run log (.json, or the .txt beside it) of a run on real ports, with its recording beside it" };
        var json = new Option<bool>("--json") { Description = "Print one JSON object: the run's outcome and times from its log, the burn figures from the replay (as engrave --simulate --json)" };
        var burned = new Option<string?>("--burned") { Description = "Write what the run burned as a PNG on the job's pixel grid (black = burned)" };
        var dose = new Option<string?>("--dose") { Description = "Write the run's pulse map as a PNG, 4 x 4 cells a pixel, grey = pulses (black = the most)" };
        var simOptions = MachineOptions.SimOptionsOption();
        var simSeed = MachineOptions.SimSeedOption();
        var command = new Command("replay", "Replay a recorded run's bytes at their times through the twin: the dose map, edges and pulses on white it actually burned")
        {
            log, json, burned, dose, simOptions, simSeed,
        };
        command.SetAction((result, ct) => RunAsync(result, result.GetRequiredValue(log), result.GetValue(json), result.GetValue(burned), result.GetValue(dose), MachineOptions.SimulatorOptions(result, simOptions, simSeed, string.Empty), ct));
        return command;
    }

    private static async Task<int> RunAsync(ParseResult result, string logPath, bool json, string? burnedPath, string? dosePath, SimulatorOptions baseOptions, CancellationToken cancellationToken)
    {
        OptionChecks.OutputFile(burnedPath, "--burned");
        OptionChecks.OutputFile(dosePath, "--dose");
        var jsonPath = logPath.EndsWith(".txt", StringComparison.OrdinalIgnoreCase) ? Path.ChangeExtension(logPath, ".json") : logPath;
        var record = RunLogStore.Read(jsonPath);
        var recording = record.Recording
            ?? throw new UsageException($"{logPath}: the run has no recording (only runs on real ports record their bytes), so there is nothing to replay");
        if (recording.File.Length == 0 || Path.GetFileName(recording.File) != recording.File)
        {
            throw new UsageException($"{logPath}: the recording's file \"{recording.File}\" is not a file name in the log's folder");
        }

        if (recording.Truncated)
        {
            throw new UsageException($"{logPath}: the recording is truncated (it reached its size cap), so the rest of the run is not in it and its burn cannot be replayed");
        }

        if (record.Layers is not null)
        {
            throw new UsageException($"{logPath}: a job of layers cannot be replayed yet; replay is for one image or drawing");
        }

        var spec = RunReplay.ToJobSpec(record);
        MachineProfileValidator.Validate(spec.Profile, $"{logPath}: profile");
        var events = WireRecording.Read(Path.Combine(Path.GetDirectoryName(Path.GetFullPath(jsonPath))!, recording.File));
        PreparedJob? job = null;
        PreparedDrawing? drawing = null;
        if (record.Drawing is { } loggedDrawing)
        {
            drawing = PreparedDrawing.Prepare(spec, loggedDrawing.ToVectorOptions());
            if (burnedPath is not null || dosePath is not null)
            {
                throw new UsageException("--burned and --dose are for images; a drawing's figures are in --json (pathDeviationUm, pulseSpacingUm)");
            }
        }
        else
        {
            job = PreparedJob.Prepare(spec);
        }

        // The devices the run spoke to: the stage's firmware as it reported it (a 5.06 refuses what a 5.23 takes). The host's
        // lateness is in the recorded times already, so the replaying host is never late.
        // The stages start where they reported they stood, so homing takes the time it took.
        var options = baseOptions with { HostLateness = HostLateness.None, RealTime = false, FaultSpec = null, StartMicrosteps = WireReplay.StartMicrosteps(spec.Profile, events) };
        if (record.Devices.FirstOrDefault(d => d.Role == "x axis") is { } x && decimal.TryParse(x.Firmware, NumberStyles.AllowDecimalPoint, CultureInfo.InvariantCulture, out var firmware))
        {
            options = options with { FirmwareVersion = (int)Math.Round(firmware * 100) };
        }

        RunSimulation simulation;
        BurnReport? burn = null;
        var machine = SimulatedMachine.CreateInProcess(spec.Profile, options);
        await using (machine.ConfigureAwait(false))
        {
            var inspector = new BurnInspector(machine);
            inspector.Begin();
            await WireReplay.RunAsync(machine, events, cancellationToken).ConfigureAwait(false);
            simulation = job is not null ? inspector.Inspect(job) : inspector.InspectDrawing(drawing!);
            burn = inspector.Report;
        }

        if (burnedPath is not null && burn is not null)
        {
            burn.WritePng(burnedPath);
        }

        if (dosePath is not null && burn is not null)
        {
            burn.WriteDosePng(dosePath);
        }

        var files = new RunLogFiles(Path.GetFullPath(jsonPath), Path.ChangeExtension(Path.GetFullPath(jsonPath), ".txt"));
        var summary = EngraveSummary.From(record with { Simulation = simulation }, files, burnedPath, burn is null ? null : dosePath, null);
        var stdout = result.InvocationConfiguration.Output;
        if (json)
        {
            CliJson.Write(stdout, summary);
        }
        else
        {
            stdout.WriteLine($"Replayed {events.Count} recorded writes and reads of {files.JsonPath} through the twin (seed {options.Seed}):");
            EngraveCommand.WriteText(stdout, summary);
        }

        return CliRunner.Ok;
    }
}
