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
/// the flight recorder beside it; the devices are the twin's, the figures those of `engrave --simulate` (a job of layers:
/// each layer's, from its recorded start to the next's, its layers read again from the job file). Exit 2 for a log
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
        var model = new Option<bool>("--model-latency") { Description = "Let the twin's adapters draw their latency (--sim-options adapterLatency) instead of taking each write's delay from its recorded reply" };
        var simOptions = MachineOptions.SimOptionsOption();
        var simSeed = MachineOptions.SimSeedOption();
        var command = new Command("replay", "Replay a recorded run's bytes at their times through the twin: the dose map, edges and pulses on white it actually burned")
        {
            log, json, burned, dose, model, simOptions, simSeed,
        };
        command.SetAction((result, ct) => RunAsync(result, result.GetRequiredValue(log), result.GetValue(json), result.GetValue(burned), result.GetValue(dose), result.GetValue(model), MachineOptions.SimulatorOptions(result, simOptions, simSeed, string.Empty), ct));
        return command;
    }

    private static async Task<int> RunAsync(ParseResult result, string logPath, bool json, string? burnedPath, string? dosePath, bool modelLatency, SimulatorOptions baseOptions, CancellationToken cancellationToken)
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

        var events = WireRecording.Read(Path.Combine(Path.GetDirectoryName(Path.GetFullPath(jsonPath))!, recording.File));
        BurnReport? burn = null;
        ReplayUncertainty? uncertainty = null;
        ReplaySetup setup;
        if (record.Layers is { } loggedLayers)
        {
            if (burnedPath is not null || dosePath is not null)
            {
                throw new UsageException("--burned and --dose are for one image; a job of layers has its figures layer by layer in --json (layers[].simulation)");
            }

            // Each layer read again from the job file the log names, checked against its SHA-256, as a repeat of the run does.
            var profile = record.Profile ?? MachineProfile.Default;
            MachineProfileValidator.Validate(profile, $"{logPath}: profile");
            var (layers, _) = RunReplay.ToLayers(record, resume: false, logPath, burning: false);
            var parts = LayeredJob.Prepare(layers, profile).Layers;
            setup = RecordedRunReplay.Setup(record, profile, events, baseOptions, !modelLatency);
            var simulations = await RecordedRunReplay.ReplayLayersAsync(parts, profile, events, setup, cancellationToken).ConfigureAwait(false);
            record = record with { Layers = [.. loggedLayers.Select((l, i) => l with { Simulation = simulations[i] })] };
        }
        else
        {
            var spec = RunReplay.ToJobSpec(record);
            MachineProfileValidator.Validate(spec.Profile, $"{logPath}: profile");
            // The log says which kind ran: the one place the replay chooses how to plan it again.
            EngraveJob job;
            if (record.Drawing is { } loggedDrawing)
            {
                job = PreparedDrawing.Prepare(spec, loggedDrawing.ToVectorOptions());
                if (burnedPath is not null || dosePath is not null)
                {
                    throw new UsageException("--burned and --dose are for images; a drawing's figures are in --json (pathDeviationUm, pulseSpacingUm)");
                }
            }
            else
            {
                job = PreparedJob.Prepare(spec);
            }

            setup = RecordedRunReplay.Setup(record, spec.Profile, events, baseOptions, !modelLatency);
            (var simulation, burn, uncertainty) = await RecordedRunReplay.ReplayWithUncertaintyAsync(job, spec.Profile, events, setup, cancellationToken).ConfigureAwait(false);
            record = record with { Simulation = simulation };
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
        var summary = EngraveSummary.From(record, files, burnedPath, burn is null ? null : dosePath, null) with
        {
            Replay = uncertainty is null ? null : new ReplayUncertaintyReport(uncertainty.Summary(), uncertainty),
        };
        var stdout = result.InvocationConfiguration.Output;
        if (json)
        {
            CliJson.Write(stdout, summary);
        }
        else
        {
            stdout.WriteLine($"Replayed {events.Count} recorded writes and reads of {files.JsonPath} through the twin (seed {setup.Options.Seed}; {(setup.Delays is null ? "the twin's adapter latency" : "each write's delay from what the recording shows")}):");
            EngraveCommand.WriteText(stdout, summary);
            if (uncertainty is not null)
            {
                // What the recording cannot tell, beside what the estimate burned: never counted as pulses on white.
                stdout.WriteLine($"Uncertain: {uncertainty.Summary()}");
            }
        }

        return CliRunner.Ok;
    }
}

/// <summary>A replay's uncertainty as `replay --json` prints it under <c>replay</c>: the one line, then the figures.</summary>
internal sealed record ReplayUncertaintyReport(string Summary, ReplayUncertainty Figures);
