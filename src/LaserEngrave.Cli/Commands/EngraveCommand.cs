using System.Diagnostics;
using System.CommandLine;
using System.Globalization;
using System.Runtime.ExceptionServices;
using System.Text.Json;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Machines;
using LaserEngrave.Machines.Runs;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Cli.Commands;

/// <summary>`laserengrave engrave IMAGE (size) ... (--simulate | --stage-port P --laser-port Q)`: runs a job, shows its progress and logs it.</summary>
/// <remarks>
/// Exit code 0 only when every run was burned; 1 when the run was aborted, failed or refused by preflight (the log is
/// written in every one of those cases); 2 for bad input, before anything opens.
/// </remarks>
internal static class EngraveCommand
{
    /// <summary>The largest --burned-scale: 16 x 16 image pixels a job pixel is enough to see one pixel on a screen.</summary>
    private const int MaxBurnedScale = 16;

    public static Command Create()
    {
        var o = new EngraveOptions();
        var command = new Command("engrave", "Engrave an image: plan, run on the machine or the simulator with a progress bar, and log the run");
        o.AddTo(command);
        command.SetAction((result, ct) => RunAsync(result, o, ct));
        return command;
    }

    private static async Task<int> RunAsync(ParseResult result, EngraveOptions o, CancellationToken cancellationToken)
    {
        var stderr = result.InvocationConfiguration.Error;
        o.Machine.Validate(result);
        var outputs = BindOutputs(result, o);
        var choice = ChooseJob(result, o, outputs);
        var job = choice.Job;
        var seam = LogSeam.Value;
        var store = new RunLogStore(result.GetValue(o.LogDir) ?? RunLogStore.DefaultFolder, seam?.Files);
        var run = new EngraveRun(
            new RunRequest
            {
                Job = job,
                Notes = result.GetValue(o.Notes),
                SampleId = result.GetValue(o.Sample),
                RepeatOf = choice.RepeatOf,
                ResumeFrom = choice.ResumeFrom,
                ResumeLayers = choice.ResumeLayers,
                JobFile = choice.JobFile,
                Home = result.GetValue(o.Home),
                AcceptNoWatchdog = result.GetValue(o.Machine.AcceptNoWatchdog),
            },
            // The record is the only thing that resumes a run: a folder that fails during the run must not lose it.
            new RunLog(FallbackRunLogWriter.For(store, seam?.DataFolder ?? FallbackRunLogWriter.DefaultDataFolder, seam?.Files), store.CheckWritable));

        // Refused before any port opens, nothing moved and the stage not homed: bad input (exit 2), in the use case's words.
        if (run.Check() is { } refusal)
        {
            if (refusal.Cause is { } cause)
            {
                ExceptionDispatchInfo.Throw(cause);
            }

            throw new UsageException(refusal.Message);
        }

        foreach (var warning in choice.Warnings)
        {
            stderr.WriteLine($"warning: {warning}");
        }

        var profile = job.Spec.Profile;
        o.Machine.RefuseUnacceptedNoWatchdog(result, profile);

        // While the machine opens and runs (the simulation on one thread), another thread prepares the JSON writers of
        // the log and the summary, which would otherwise add their compiling time (a tenth of a second) after the run.
        var json = result.GetValue(o.Json);
        var prepareJson = Task.Run(() =>
        {
            RunRecordJson.Prepare();
            if (json)
            {
                CliJson.Prepare(typeof(EngraveSummary));
            }
        });
        // What was understood, before any port opens: a size, origin or frequency read otherwise than meant shows here.
        foreach (var line in JobUnderstood.Lines(job))
        {
            stderr.WriteLine(line);
        }
        var (ended, burn, wallSeconds) = await RunOnMachineAsync(result, o, run, store.Folder, cancellationToken).ConfigureAwait(false);
        await prepareJson.ConfigureAwait(false);
        return Report(result, json, ended, burn, outputs, wallSeconds);
    }

    /// <summary>Opens the machine the options name, runs the job on it with its progress on stderr, and closes it.</summary>
    /// <returns>How the run ended, on the twin what it burned, and the wall time the run took.</returns>
    private static async Task<(RunEnd Ended, BurnReport? Burn, double? WallSeconds)> RunOnMachineAsync(ParseResult result, EngraveOptions o, EngraveRun run, string logFolder, CancellationToken cancellationToken)
    {
        var stderr = result.InvocationConfiguration.Error;
        var job = run.Request.Job;
        var profile = job.Spec.Profile;
        RunEnd ended;
        double? wallSeconds = null;
        ITwinInspector? inspector = null;
        // On real ports every byte in and out is recorded beside the log, so the run's burn can be replayed (`laserengrave replay`).
        using var recorder = result.GetValue(o.Machine.Simulate) ? null : new WireRecorder(Path.Combine(logFolder, $"wire_{DateTime.UtcNow:yyyy-MM-dd_HHmmss}_{Guid.NewGuid().ToString("N")[..8]}.jsonl"), TimeProvider.System);
        OpenMachine opened;
        try
        {
            opened = o.Machine.Open(result, profile, recorder);
        }
        catch
        {
            recorder?.Discard();
            throw;
        }

        await using (opened.ConfigureAwait(false))
        {
            inspector = opened.Twin;
            var session = run.Open(opened.Engraving, recorder);
            var printer = new ProgressPrinter(stderr, terminal: ReferenceEquals(stderr, Console.Error) && !Console.IsErrorRedirected)
            {
                Job = job,
            };
            // The tolerance a late switch-on is judged by, as the profile gives it (docs/execution.md, "Late switchings").
            stderr.WriteLine("preflight: " + RunSummaryText.EdgeTolerance(profile.EdgeToleranceUm));
            var wall = Stopwatch.StartNew();
            try
            {
                ended = await EngraveRun.RunAsync(session, printer, cancellationToken).ConfigureAwait(false);
            }
            finally
            {
                printer.Finish();
                wallSeconds = wall.Elapsed.TotalSeconds;
            }
        }

        return (ended, inspector?.Report, wallSeconds);
    }

    /// <summary>What the simulator's burn is written to after the run: --burned (at --burned-scale) and --dose.</summary>
    private sealed record BurnOutputs(string? BurnedPath, int? BurnedScale, string? DosePath);

    /// <summary>The one job the session runs, whichever kind the options name, with what its log says of where it came from.</summary>
    private sealed record JobChoice(EngraveJob Job, IEnumerable<string> Warnings, string? RepeatOf = null, RunStopPoint? ResumeFrom = null, LayerResumePoint? ResumeLayers = null, string? JobFile = null);

    private static BurnOutputs BindOutputs(ParseResult result, EngraveOptions o)
    {
        var burnedPath = result.GetValue(o.Burned);
        if (burnedPath is not null && !result.GetValue(o.Machine.Simulate))
        {
            throw new UsageException("--burned needs --simulate: only the simulator knows what was burned");
        }

        OptionChecks.OutputFile(burnedPath, "--burned");
        var burnedScale = result.GetValue(o.BurnedScale);
        if (burnedScale is not null && burnedPath is null)
        {
            throw new UsageException("--burned-scale needs --burned: it sizes that image");
        }

        OptionChecks.InRange(burnedScale, 1, MaxBurnedScale, "--burned-scale", " image pixels a job pixel", "to look at a small job's burned.png");
        return new BurnOutputs(burnedPath, burnedScale, result.GetValue(o.Dose));
    }

    private static JobChoice ChooseJob(ParseResult result, EngraveOptions o, BurnOutputs outputs)
    {
        var passes = result.GetValue(o.Passes);
        if (passes is { } n && JobRules.Passes(n) is { } rule)
        {
            throw new UsageException($"--passes {n}: {rule}");
        }

        if (result.GetValue(o.JobFile) is null && OptionChecks.IsGiven(result, o.Counter))
        {
            throw new UsageException("--counter is for --job: a job file's marks number from it (a repeated or resumed run's log names its own)");
        }

        if (result.GetValue(o.JobFile) is { } jobFile)
        {
            if (new Option[] { o.FromLog, o.Resume, o.Passes, o.Burned, o.Dose }.FirstOrDefault(option => OptionChecks.IsGiven(result, option)) is { } other)
            {
                throw new UsageException($"{other.Name} with --job: {(other == o.Passes ? "each layer has its own passes" : other == o.Burned || other == o.Dose ? "--burned and --dose are for one image" : "a job of layers is repeated or resumed by --from-log LOG alone (the log names its job file)")}");
            }

            var layered = LayerCommands.Prepare(result, jobFile, o.Job, o.Vector, result.GetValue(o.Counter), result.GetValue(o.Sample));
            return new JobChoice(layered, LayerCommands.Warnings(layered), JobFile: jobFile);
        }

        // With IMAGE too, the image's way refuses the pair before any log is read.
        if (result.GetValue(o.Job.Image) is null && result.GetValue(o.FromLog) is { } layersLog && RunLogStore.Read(layersLog).Layers is not null)
        {
            if (new Option[] { o.Passes, o.Burned, o.Dose }.FirstOrDefault(option => OptionChecks.IsGiven(result, option)) is { } other)
            {
                throw new UsageException($"{other.Name} with --from-log of a job of layers: {(other == o.Passes ? "each layer has its own passes" : "--burned and --dose are for one image")}");
            }

            var (layered, layeredFile, resumeLayers) = LayerCommands.FromLog(result, layersLog, result.GetValue(o.Resume), o.Job, o.Vector);
            return new JobChoice(layered, LayerCommands.Warnings(layered), Path.GetFullPath(layersLog), ResumeLayers: resumeLayers, JobFile: layeredFile);
        }

        if (IsDrawingJob(result, o))
        {
            if (outputs.BurnedPath is not null || outputs.DosePath is not null)
            {
                throw new UsageException("--burned and --dose are for images; a drawing's figures are in the log and in --json (pathDeviationUm, pulseSpacingUm)");
            }

            var (drawing, repeatOf, resumeFrom) = BindDrawingJob(result, o, passes);
            return new JobChoice(drawing, drawing.Warnings, repeatOf, resumeFrom);
        }

        return ChooseImage(result, o, passes, outputs.BurnedScale);
    }

    /// <summary>An image's job, from IMAGE or a run log, refused before any port opens when the plan alone shows it cannot burn as asked.</summary>
    private static JobChoice ChooseImage(ParseResult result, EngraveOptions o, int? passes, int? burnedScale)
    {
        var (spec, repeatOf, resumeFrom) = BindJob(result, o);
        spec = spec with { Passes = passes ?? spec.Passes };
        var prepared = PreparedJob.Prepare(spec);
        if (burnedScale is { } scale && PngWriter.ScaledPixels(prepared.Mask.Width, prepared.Mask.Height, scale) > PngWriter.MaxScaledPixels)
        {
            throw new UsageException(string.Create(CultureInfo.InvariantCulture, $"--burned-scale {scale}: the {prepared.Mask.Width} x {prepared.Mask.Height} px job would make a burned image of {PngWriter.ScaledPixels(prepared.Mask.Width, prepared.Mask.Height, scale):N0} pixels, more than the {PngWriter.MaxScaledPixels:N0} allowed; use a smaller scale"));
        }

        if (prepared.EngraveProblem is { } tooShort)
        {
            // Known from the plan alone: refused before any port opens, as preflight would refuse it later.
            throw new UsageException(tooShort);
        }

        if (prepared.Plan.Timing is not null && SpeedHold.Problem(prepared.Spec.Process.BurnSpeedMmPerS, prepared.Spec.Profile, o.Machine.ExpectsScheduledSwitchOns(result, prepared.Spec.Profile)) is { } tooFast)
        {
            // The edge tolerance against this computer's lateness: named before any port opens, not as timing doubts mid-run.
            throw new UsageException(tooFast);
        }

        return new JobChoice(prepared, prepared.Warnings.Select(w => w.Message), repeatOf, resumeFrom);
    }

    /// <summary>The run's end as `engrave` says it: the counter, the log's place, the burn's images, the summary, and the exit code.</summary>
    private static int Report(ParseResult result, bool json, RunEnd ended, BurnReport? burn, BurnOutputs outputs, double? wallSeconds)
    {
        var stdout = result.InvocationConfiguration.Output;
        var stderr = result.InvocationConfiguration.Error;
        var engraved = ended.Result;
        var record = engraved.Record;
        if (ended.NextMarkNumber is { } next)
        {
            stderr.WriteLine(string.Create(CultureInfo.InvariantCulture, $"marks: the sample counter's next number is {next}"));
        }

        if (ended.CounterProblem is { } counterProblem)
        {
            stderr.WriteLine($"warning: the sample counter was not advanced: {counterProblem}");
        }

        if (engraved.Files is not { } files)
        {
            // The run happened: say so first, in one line, then keep what the log would have said on stderr and the
            // record itself on stdout with --json (what --resume needs, to be saved by hand), and fail (not "bad input").
            var why = engraved.LogError?.Message ?? "no log was written";
            var outcome = record.Outcome.ToString().ToLowerInvariant();
            stderr.WriteLine($"laserengrave: the run ended ({outcome}) but its log could not be written{(json ? "; the record is in the JSON on stdout (runLog)" : ", so its summary follows")}: {why}");
            stderr.Write(RunSummaryText.Format(record));
            if (json)
            {
                CliJson.Write(stdout, EngraveSummary.From(record, null, null, null, null) with { RunLog = RecordElement(record) });
            }

            throw new InvalidOperationException($"the run ended ({outcome}) and its log was not written (see the first line above)", engraved.LogError);
        }

        if (files.Notice is { } notice)
        {
            // The first line after the run, before the summary: the log is not where it was asked to be.
            stderr.WriteLine($"laserengrave: {notice}");
        }

        if (outputs.BurnedPath is { } burnedPath && burn is not null)
        {
            burn.WritePng(burnedPath, outputs.BurnedScale ?? 1);
        }

        if (outputs.DosePath is { } dosePath && burn is not null)
        {
            burn.WriteDosePng(dosePath);
        }

        var summary = EngraveSummary.From(record, files, outputs.BurnedPath, burn is null ? null : outputs.DosePath, wallSeconds);
        if (json)
        {
            CliJson.Write(stdout, summary with { LogNotice = files.Notice, RunLog = RecordElement(record) });
        }
        else
        {
            WriteText(stdout, summary);
        }

        if (engraved.Error is { } error)
        {
            ExceptionDispatchInfo.Throw(error);
        }

        if (record.Outcome != RunOutcome.Completed)
        {
            if (record.Fault is { } fault)
            {
                stderr.WriteLine($"laserengrave: laser off: {RunSummaryText.LaserOff(fault)}");
            }

            stderr.WriteLine($"laserengrave: run {summary.Outcome}: {record.Fault?.Message ?? "no reason given"} (log: {files.JsonPath})");

            return CliRunner.Failure;
        }

        return CliRunner.Ok;
    }

    /// <summary>
    /// Tests only: the file system the run log is written with and the data folder it falls back to, for this call
    /// (an <see cref="AsyncLocal{T}"/>, so tests running side by side do not see each other's).
    /// </summary>
    internal static readonly AsyncLocal<(RunLogFileSystem Files, string DataFolder)?> LogSeam = new();

    // The run record exactly as the log's JSON holds it (docs/run-log.md), for --json's runLog.
    private static JsonElement RecordElement(RunRecord record)
    {
        using var document = JsonDocument.Parse(RunRecordJson.Serialize(record));
        return document.RootElement.Clone();
    }

    /// <summary>Whether the job is a drawing: IMAGE is a .dxf or .svg, or the log repeated is a drawing's.</summary>
    /// <remarks>With both IMAGE and --from-log the image's way refuses the pair, before the log is read.</remarks>
    private static bool IsDrawingJob(ParseResult result, EngraveOptions o) =>
        result.GetValue(o.Job.Image) is { } image
            ? Core.Vectors.DrawingReader.IsDrawing(image) && result.GetValue(o.FromLog) is null
            : result.GetValue(o.FromLog) is { } fromLog && RunLogStore.Read(fromLog).Drawing is not null;

    /// <summary>The drawing's job from the options, or from a drawing's run log (the file checked against its SHA-256).</summary>
    private static (PreparedDrawing Drawing, string? RepeatOf, RunStopPoint? ResumeFrom) BindDrawingJob(ParseResult result, EngraveOptions o, int? passes)
    {
        if (result.GetValue(o.FromLog) is null)
        {
            if (result.GetValue(o.Resume))
            {
                throw new UsageException("--resume needs --from-log: the log says where the run stopped");
            }

            var fresh = VectorCommands.Prepare(result, o.Job, o.Vector);
            return (passes is { } n ? Rebuild(fresh, fresh.Spec with { Passes = n }) : fresh, null, null);
        }

        if (OptionChecks.IsGiven(result, o.Vector.ToleranceUm) || OptionChecks.IsGiven(result, o.Vector.Fill) || OptionChecks.IsGiven(result, o.Vector.FillPitchUm) || result.GetValue(o.Vector.DrawingOrder))
        {
            throw new UsageException("drawing options with --from-log: a repeated run takes every parameter from its log; leave them out");
        }

        var (spec, repeatOf, resumeFrom) = BindJob(result, o);
        var logged = RunLogStore.Read(result.GetValue(o.FromLog)!);
        return (PreparedDrawing.Prepare(spec, logged.Drawing!.ToVectorOptions()), repeatOf, resumeFrom);

        static PreparedDrawing Rebuild(PreparedDrawing d, JobSpec spec) => PreparedDrawing.Prepare(spec, d.Vector);
    }

    /// <summary>The job from the options, or from a run log (the image checked against its SHA-256), with the stop point to resume from.</summary>
    private static (JobSpec Spec, string? RepeatOf, RunStopPoint? ResumeFrom) BindJob(ParseResult result, EngraveOptions o)
    {
        var fromLog = result.GetValue(o.FromLog);
        var resume = result.GetValue(o.Resume);
        if (fromLog is null)
        {
            return resume
                ? throw new UsageException("--resume needs --from-log: the log says where the run stopped")
                : (o.Job.Bind(result), null, null);
        }

        if (result.GetValue(o.Job.Image) is { } image)
        {
            throw new UsageException($"give IMAGE ({image}) or --from-log, not both: a repeated run takes its image and parameters from the log");
        }

        if (o.Job.Given(result).Concat(OptionChecks.IsGiven(result, o.Passes) ? [o.Passes.Name] : []).FirstOrDefault() is { } ignored)
        {
            throw new UsageException($"{ignored} with --from-log: a repeated run takes every parameter from its log, so {ignored} would be ignored; leave it out, or give IMAGE instead of --from-log");
        }

        var logged = RunLogStore.Read(fromLog);
        // A log is a file anyone can edit: ToJobSpec checks every value it takes from it (RunReplay.Check) before anything moves.
        var spec = RunReplay.ToJobSpec(logged, fromLog);

        if (!resume)
        {
            return (spec, Path.GetFullPath(fromLog), null);
        }

        _ = logged.StoppedAt
            ?? throw new UsageException($"{fromLog}: the run {logged.Outcome.ToString().ToLowerInvariant()} with no stop point, so there is nothing to resume; repeat it without --resume");
        // A log of an older schema version may count the moves of an older plan: its stop point in today's plan.
        var stop = RunReplay.StopPointInPlan(logged, () => PreparedJob.Prepare(spec).Plan);
        return (spec, Path.GetFullPath(fromLog), stop);
    }

    internal static void WriteText(TextWriter output, EngraveSummary s)
    {
        var c = CultureInfo.InvariantCulture;
        var clock = s.Simulated ? " (simulated time)" : string.Empty;
        output.WriteLine(string.Create(c, $"Outcome:          {s.Outcome}{(s.Fault is null ? string.Empty : $": {s.Fault}")}"));
        output.WriteLine(s.PathDeviationUm is null && !s.Drawing
            ? string.Create(c, $"Done:             {s.RowsDone} of {s.RowsTotal} rows, {s.RunsDone} of {s.RunsTotal} {(s.Mode == "dots" ? "dots" : "burn runs")}")
            : string.Create(c, $"Done:             {s.RowsDone} of {s.RowsTotal} strokes, {s.RunsDone} of {s.RunsTotal} paths"));
        if (s.Passes > 1)
        {
            output.WriteLine(string.Create(c, $"Passes:           {s.PassesDone ?? 0} of {s.Passes} done (rows and runs above: the last pass)"));
        }

        output.WriteLine(string.Create(c, $"Duration:         {RunSummaryText.Duration(s.DurationSeconds)}, estimated {RunSummaryText.Duration(s.EstimatedSeconds)}{clock}; engraving {RunSummaryText.Duration(s.EngravingSeconds)}, estimated {RunSummaryText.Duration(s.EstimatedEngravingSeconds)}"));
        output.WriteLine(string.Create(c, $"Laser on:         {RunSummaryText.Duration(s.LaserOnSeconds)}"));
        if (s.PathDeviationUm is { } deviation && s.PulseSpacingUm is { } spacing)
        {
            output.WriteLine(string.Create(c, $"Path deviation:   mean {deviation.Mean:0.###} µm, largest {deviation.Max:0.###} µm; {s.LaserOnTravelCount} pulses off the path"));
            output.WriteLine(string.Create(c, $"Pulse spacing:    {spacing.Min:0.###}..{spacing.Max:0.###} µm, mean {spacing.Mean:0.####} µm (v/f = {s.ExpectedSpacingUm:0.####} µm)"));
            if (s.Dwells is { } pathDwells)
            {
                output.WriteLine(string.Create(c, $"Dwells:           {pathDwells.Count} ({pathDwells.Pulses} pulses with the stage still)"));
            }

            if (s.WallSeconds is { } wall && wall > 0)
            {
                output.WriteLine(string.Create(c, $"Simulated in:     {wall:0.###} s of wall time ({s.DurationSeconds / wall:0} x real time, seed {s.SimSeed})"));
            }
        }

        if (s.MissingPixels is { } missing && s.ExtraPixels is { } extra && !s.Drawing)
        {
            output.WriteLine(string.Create(c, $"Burned vs mask:   {missing} pixels missing, {extra} extra, {s.LaserOnTravelCount} pulses off the black"));
            if (s.Edges is { } edges)
            {
                output.WriteLine(string.Create(c, $"Edges:            {edges.Count}, mean error {edges.MeanErrorUm:0.##} µm, largest {edges.MaxErrorUm:0.##} µm"));
            }

            if (s.Dwells is { } dwells)
            {
                output.WriteLine(string.Create(c, $"Dwells:           {dwells.Count} ({dwells.Pulses} pulses with the stage still)"));
            }

            if (s.Mode == "dots")
            {
                output.WriteLine(string.Create(c, $"Dot mode:         {s.PulsesPerDot} pulses per dot, {s.PulsesWhileMoving} pulses while the stage moved"));
            }

            if (s.PulsesPerPixel is { } ppp)
            {
                output.WriteLine(string.Create(c, $"Pulses per pixel: min {ppp.Min}, mean {ppp.Mean:0.#}, max {ppp.Max} ({s.Pulses} pulses, seed {s.SimSeed})"));
            }

            if (s.WallSeconds is { } wall && wall > 0)
            {
                output.WriteLine(string.Create(c, $"Simulated in:     {wall:0.###} s of wall time ({s.DurationSeconds / wall:0} x real time)"));
            }
            if (s.Resumed)
            {
                // Each --simulate starts a fresh simulator: what the stopped run burned is not on this one, so it is not checked here.
                output.WriteLine("                  (this run resumed another: the pixels that run burned are not checked here)");
            }
        }

        if (s.BurnedPath is not null)
        {
            output.WriteLine($"Burned image:     {s.BurnedPath}");
        }

        if (s.DosePath is not null)
        {
            output.WriteLine($"Pulse map:        {s.DosePath}");
        }

        foreach (var (layer, i) in (s.Layers ?? []).Select((l, i) => (l, i + 1)))
        {
            var ended = RunSummaryText.LayerEnd(layer);
            var twin = layer.Simulation?.Path is { } path
                ? string.Create(c, $"; deviation max {path.DeviationUm.Max:0.##} µm, spacing {path.PulseSpacingUm.Min:0.###}..{path.PulseSpacingUm.Max:0.###} µm")
                : layer.Simulation is { } sim ? string.Create(c, $"; {sim.MissingPixels} pixels missing, {sim.ExtraPixels} extra") : string.Empty;
            output.WriteLine(string.Create(c, $"Layer {i}:          \"{layer.Name}\" {ended}, {layer.PassesDone} of {layer.Passes} passes, engraving {RunSummaryText.Duration(layer.EngravingSeconds)} (estimated {RunSummaryText.Duration(layer.EstimatedEngravingSeconds)}){twin}"));
        }

        output.WriteLine($"Log:              {s.LogPath}");
        output.WriteLine($"Summary:          {s.SummaryPath}");
    }

    /// <summary>The options of `engrave`: the job's, the machine's, and the run's own.</summary>
    private sealed class EngraveOptions
    {
        public EngraveOptions()
        {
            // IMAGE may be left out when --from-log gives the job.
            Job.Image.Arity = ArgumentArity.ZeroOrOne;
        }

        public JobOptions Job { get; } = new();

        public VectorOptionSet Vector { get; } = new();

        public MachineOptions Machine { get; } = new();

        public Option<string?> LogDir { get; } = LogCommand.LogDirOption();

        public Option<string?> Burned { get; } = new("--burned") { Description = "With --simulate: write what was burned as a PNG on the job's pixel grid (black = burned)" };

        public Option<int?> BurnedScale { get; } = new("--burned-scale") { Description = "With --burned: draw each job pixel as N x N image pixels (1..16, default 1), so a small job's image is big enough to look at" };

        public Option<string?> Dose { get; } = new("--dose") { Description = "With --simulate: write the pulse map as a PNG, 4 x 4 cells a pixel, grey = pulses (black = the most), to see overburn" };

        public Option<string?> Notes { get; } = new("--notes") { Description = "Notes for the run log (focus, material, anything to remember)" };

        public Option<string?> Sample { get; } = new("--sample") { Description = "Sample ID for the run log; also part of the log's file name" };

        public Option<bool> Json { get; } = new("--json") { Description = "Print one JSON object with the outcome, times, counts and the log's path; durationSeconds and estimatedSeconds are the whole run (preflight and homing included), engravingSeconds and estimatedEngravingSeconds the engraving alone" };

        public Option<string?> FromLog { get; } = new("--from-log") { Description = "Repeat the run of this log (its image, unchanged, and all its parameters) instead of giving IMAGE" };

        public Option<bool> Resume { get; } = new("--resume") { Description = "With --from-log: continue that run from where it stopped instead of starting over" };

        public Option<bool> Home { get; } = new("--home") { Description = "Home both axes before the run even if they are homed" };

        public Option<string?> JobFile { get; } = LayerCommands.JobOption();

        public Option<string?> Counter { get; } = new("--counter") { Description = $"With --job: the sample counter its marks number from (default {Core.Marks.MarkCounter.FileName} with the app's settings)" };

        public Option<int?> Passes { get; } = new("--passes") { Description = "Burn the plan N times over the same place, one pass after the other (1..100, default 1)" };

        public void AddTo(Command command)
        {
            Job.AddTo(command);
            Vector.AddTo(command);
            Machine.AddTo(command);
            foreach (var option in new Option[] { LogDir, Burned, BurnedScale, Dose, Notes, Sample, Json, FromLog, Resume, Home, Passes, JobFile, Counter })
            {
                command.Options.Add(option);
            }
        }
    }
}

/// <summary>What `engrave --json` prints: the outcome, times, counts, the log's files and, on the simulator, the burn check.</summary>
internal sealed record EngraveSummary(
    string Outcome,
    string? Fault,
    long? StoppedAtMove,
    bool Simulated,
    bool Resumed,
    double DurationSeconds,
    double? WallSeconds,
    double EngravingSeconds,
    double EstimatedSeconds,
    double EstimatedEngravingSeconds,
    double LaserOnSeconds,
    int RowsDone,
    int RowsTotal,
    long RunsDone,
    long RunsTotal,
    string? LogPath,
    string? SummaryPath,
    string? BurnedPath,
    string? DosePath,
    int? SimSeed,
    long? Pulses,
    long? MissingPixels,
    long? ExtraPixels,
    long? LaserOnTravelCount,
    EdgeErrors? Edges,
    DwellCounts? Dwells,
    PulseCountRange? PulsesPerPixel,
    int Passes,
    int? PassesDone,
    string Mode,
    int PulsesPerDot,
    long? PulsesWhileMoving,
    MeanMax? PathDeviationUm,
    SpacingRange? PulseSpacingUm,
    double? ExpectedSpacingUm,
    bool Drawing,
    IReadOnlyList<RunLayer>? Layers,
    LateSwitches? LateSwitches)
{
    /// <summary>
    /// The one line saying the log went to a fallback folder and why (docs/run-log.md); null when it is where it was asked
    /// to be. After the fields above, which stay as they were, so that a reader of them sees no change.
    /// </summary>
    public string? LogNotice { get; init; }

    /// <summary>The whole run record, as the log's JSON holds it: printed even when no log could be written, so it can be saved and resumed.</summary>
    public JsonElement? RunLog { get; init; }

    /// <summary>`replay` only: what the recording cannot tell of the burn (docs/simulator.md, "Replaying a recorded run"); absent from every other command's output.</summary>
    [System.Text.Json.Serialization.JsonIgnore(Condition = System.Text.Json.Serialization.JsonIgnoreCondition.WhenWritingNull)]
    public ReplayUncertaintyReport? Replay { get; init; }

    /// <param name="files">The log's files; null when it could not be written (the object still says how the run went).</param>
    public static EngraveSummary From(RunRecord record, RunLogFiles? files, string? burnedPath, string? dosePath, double? wallSeconds) => new(
        record.Outcome.ToString().ToLowerInvariant(),
        record.Fault?.Message,
        record.StoppedAt?.MoveIndex,
        record.Simulated,
        record.Resumed,
        record.ActualSeconds,
        wallSeconds,
        record.EngravingSeconds,
        record.EstimatedSeconds,
        record.EstimatedEngravingSeconds,
        record.LaserOnSeconds,
        record.RowsDone,
        record.RowsTotal,
        record.RunsDone,
        record.RunsTotal,
        files?.JsonPath,
        files?.TextPath,
        burnedPath is null ? null : Path.GetFullPath(burnedPath),
        dosePath is null ? null : Path.GetFullPath(dosePath),
        record.Simulation?.Seed,
        record.Simulation?.Pulses,
        record.Drawing is null ? record.Simulation?.MissingPixels : null,
        record.Drawing is null ? record.Simulation?.ExtraPixels : null,
        record.Simulation?.LaserOnTravelCount,
        record.Simulation?.Edges,
        record.Simulation?.Dwells,
        record.Drawing is null ? record.Simulation?.PulsesPerPixel : null,
        record.Passes,
        record.PassesDone,
        record.Process.Mode == PlanMode.Dots ? "dots" : "raster",
        record.Process.PulsesPerDot,
        record.Simulation?.PulsesWhileMoving,
        record.Simulation?.Path?.DeviationUm,
        record.Simulation?.Path?.PulseSpacingUm,
        record.Simulation?.Path?.ExpectedSpacingUm,
        record.Drawing is not null,
        record.Layers,
        record.LateSwitches);
}
