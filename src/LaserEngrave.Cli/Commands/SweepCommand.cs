using System.CommandLine;
using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Sweeps;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Machines;
using LaserEngrave.Simulator.Burn;

namespace LaserEngrave.Cli.Commands;

/// <summary>
/// `laserengrave sweep --rows speed=0.5,1,2 [--columns frequency=500,1000] ... (--simulate | ports)`: a grid of test cells,
/// one or two process values varied over its rows and columns, burned in one run and logged cell by cell.
/// </summary>
/// <remarks>Exit code 0 when every cell was burned, 1 when the sweep stopped (its log is still written), 2 for bad input before anything opens.</remarks>
internal static class SweepCommand
{
    public static Command Create()
    {
        var o = new SweepOptions(focusSeries: false);
        var command = new Command("sweep", "Burn a test grid: cells (filled square, line set, dot array or a small image) with one or two process values varied over rows and columns, in one run, logged cell by cell");
        o.AddTo(command);
        command.SetAction((result, ct) => RunAsync(result, o, ct));
        return command;
    }

    /// <summary>`laserengrave focus-series --focus-um -200..200:50 ...`: the sweep whose rows are focus positions (machines with a Z axis).</summary>
    public static Command CreateFocusSeries()
    {
        var o = new SweepOptions(focusSeries: true);
        var command = new Command("focus-series", "Burn a focal series (seed 002): one cell (short lines by default) per focus position around the profile's visible focus, the Z axis moved with the laser off before each; the sweep of --rows focus=..., for a machine profile with a Z axis");
        o.AddTo(command);
        command.SetAction((result, ct) => RunAsync(result, o, ct));
        return command;
    }

    private static async Task<int> RunAsync(ParseResult result, SweepOptions o, CancellationToken cancellationToken)
    {
        var stdout = result.InvocationConfiguration.Output;
        var stderr = result.InvocationConfiguration.Error;
        var plan = SweepPlan.Build(o.Bind(result));
        var json = result.GetValue(o.Json);
        if (result.GetValue(o.PlanOnly))
        {
            if (json)
            {
                CliJson.Write(stdout, SweepPlanSummary.From(plan));
            }
            else
            {
                WritePlan(stdout, plan);
            }

            return 0;
        }

        o.Machine.Validate(result);
        var simulate = result.GetValue(o.Machine.Simulate);
        var doseDir = result.GetValue(o.DoseDir);
        if (doseDir is not null && !simulate)
        {
            throw new UsageException("--dose-dir needs --simulate: only the simulator knows what was burned");
        }

        var dosePath = result.GetValue(o.Dose);
        if (dosePath is not null && !simulate)
        {
            throw new UsageException("--dose needs --simulate: only the simulator knows what was burned");
        }

        OptionChecks.OutputFile(dosePath, "--dose");

        var store = new RunLogStore(result.GetValue(o.LogDir) ?? RunLogStore.DefaultFolder);
        store.CheckWritable();
        if (doseDir is not null)
        {
            Directory.CreateDirectory(doseDir);
        }

        SweepResult swept;
        o.Machine.RefuseUnacceptedNoWatchdog(result, plan.Spec.Profile);
        if (SweepSpeedHold.Problem(plan.Cells, plan.Spec.Profile, o.Machine.ExpectsScheduledSwitchOns(result, plan.Spec.Profile)) is { } tooFast)
        {
            // Before the first cell, not 25 minutes in at the first cell this computer cannot hold (issue 34).
            throw new UsageException(tooFast);
        }

        var opened = o.Machine.Open(result, plan.Spec.Profile);
        await using (opened.ConfigureAwait(false))
        {
            var machineSession = opened.Session;
            var inspector = opened.Twin;
            var machine = new EngraveMachine(machineSession.Stage, machineSession.Gate, machineSession.TimeProvider, machineSession.StagePort, machineSession.LaserPort)
            {
                Simulated = simulate,
                Inspector = inspector,
            };
            var session = new SweepSession(machine, plan, new SweepSessionOptions
            {
                Notes = result.GetValue(o.Notes),
                SampleId = result.GetValue(o.Sample),
                Home = result.GetValue(o.Home),
                AcceptNoWatchdog = result.GetValue(o.Machine.AcceptNoWatchdog),
                Log = store,
            });
            var jobs = plan.Cells.Count + (plan.Labels is null ? 0 : 1);
            var done = 0;
            session.JobEnded += (_, e) =>
            {
                done++;
                var record = e.Result.Record;
                var what = e.Cell?.Describe() ?? "labels";
                var ppp = record.Simulation?.PulsesPerPixel is { } p ? string.Create(CultureInfo.InvariantCulture, $", pulses per pixel {p.Min}/{p.Mean:0.#}/{p.Max}") : string.Empty;
                stderr.WriteLine(string.Create(CultureInfo.InvariantCulture, $"{done} of {jobs}: {what}: {record.Outcome.ToString().ToLowerInvariant()}{ppp}"));
                if (doseDir is not null && e.Cell is { } cell && inspector?.Report is { } report)
                {
                    report.WriteDosePng(Path.Combine(doseDir, string.Create(CultureInfo.InvariantCulture, $"cell-r{cell.Row + 1}-c{cell.Column + 1}.png")));
                }
            };
            var start = inspector?.NowSeconds ?? 0;
            swept = await session.RunAsync(null, cancellationToken).ConfigureAwait(false);
            if (dosePath is not null && inspector is not null)
            {
                WholeDose(inspector, plan, start).WriteDosePng(dosePath);
            }
        }

        if (swept.Files is not { } files)
        {
            stderr.Write(SweepRecord.Format(swept.Record));
            throw new InvalidOperationException($"the sweep ended ({swept.Record.Outcome.ToString().ToLowerInvariant()}) but its log could not be written, so the summary is above: {swept.LogError?.Message ?? "no log was written"}", swept.LogError);
        }

        if (json)
        {
            CliJson.Write(stdout, new SweepRunSummary(swept.Record.Outcome.ToString().ToLowerInvariant(), swept.Record.Fault, files.JsonPath, files.TextPath, doseDir is null ? null : Path.GetFullPath(doseDir), swept.Record));
        }
        else
        {
            stdout.Write(SweepRecord.Format(swept.Record));
            stdout.WriteLine($"Log:      {files.JsonPath}");
            stdout.WriteLine($"Summary:  {files.TextPath}");
            if (doseDir is not null)
            {
                stdout.WriteLine($"Pulse maps: {Path.GetFullPath(doseDir)} (cell-rR-cC.png)");
            }

            if (dosePath is not null)
            {
                stdout.WriteLine($"Sweep's pulse map: {Path.GetFullPath(dosePath)}");
            }
        }

        return swept.Completed ? 0 : 1;
    }

    /// <summary>The pulse map of the whole sweep, labels and cells, on a grid of at most 200 cells a side over its area.</summary>
    private static BurnReport WholeDose(ITwinInspector twin, SweepPlan plan, double startSeconds)
    {
        const int MaxSide = 200;
        var spec = plan.Spec;
        var right = plan.Cells.Max(c => c.OriginXMm + c.Job.Geometry.AchievedWidthMm);
        var bottom = plan.Cells.Max(c => c.OriginYMm + c.Job.Geometry.AchievedHeightMm);
        if (plan.Labels is { } labels)
        {
            right = Math.Max(right, spec.Origin.X + labels.Geometry.AchievedWidthMm);
            bottom = Math.Max(bottom, spec.Origin.Y + labels.Geometry.AchievedHeightMm);
        }

        var microstepUm = spec.Profile.X.MicrostepUm;
        var pitchUm = Math.Max(Units.MmToUm(Math.Max(right - spec.Origin.X, bottom - spec.Origin.Y)) / MaxSide, microstepUm);
        var grid = new BurnGrid(
            StageUnits.MmToMicrosteps(spec.Origin.X, microstepUm),
            StageUnits.MmToMicrosteps(spec.Origin.Y, microstepUm),
            pitchUm / microstepUm,
            Math.Max(1, (int)Math.Ceiling(Units.MmToSteps(right - spec.Origin.X, pitchUm))),
            Math.Max(1, (int)Math.Ceiling(Units.MmToSteps(bottom - spec.Origin.Y, pitchUm))));

        // Every job's check started its own window; the whole sweep's starts where the sweep did.
        return twin.AnalyzeSince(grid, startSeconds);
    }

    private static void WritePlan(TextWriter output, SweepPlan plan)
    {
        var c = CultureInfo.InvariantCulture;
        var s = plan.Spec;
        output.WriteLine(string.Create(c, $"Grid:      {plan.RowCount} x {plan.ColumnCount} {s.Pattern.ToString().ToLowerInvariant()} cells of {s.CellMm:0.###} mm, {s.SpacingMm:0.###} mm apart; first cell at {plan.GridXMm:0.###}, {plan.GridYMm:0.###} mm"));
        output.WriteLine($"Rows:      {s.Rows}");
        output.WriteLine($"Columns:   {s.Columns?.ToString() ?? "(one)"}");
        if (plan.Labels is { } labels)
        {
            output.WriteLine(string.Create(c, $"Labels:    at {s.Origin.X:0.###}, {s.Origin.Y:0.###} mm, pixels of {labels.Geometry.PitchUm:0.#} µm, {labels.Statistics.EngravingSeconds:0.#} s"));
        }

        output.WriteLine("row col  parameters                                at (mm)          pixels  pulses/pixel  engrave s");
        foreach (var cell in plan.Cells)
        {
            var parameters = SweepParameters.Describe(cell.Parameters);
            var job = cell.Job;
            output.WriteLine(string.Create(c, $"{cell.Row + 1,3} {cell.Column + 1,3}  {parameters,-40}  {cell.OriginXMm,7:0.###}, {cell.OriginYMm,7:0.###}  {job.Mask.Width,6}  {job.Pulses.PulsesPerPixel ?? 0,12:0.##}  {job.Statistics.EngravingSeconds * job.Spec.Passes,6:0.#}{(cell.FocusZMicrosteps is { } z ? $"  Z {z}" : string.Empty)}"));
        }

        output.WriteLine(string.Create(c, $"Estimated: {SweepDuration(plan.EstimatedSeconds)} for the whole sweep (preflight, homing and the travels between cells included), engraving {SweepDuration(plan.EngravingSeconds)}"));
    }

    private static string SweepDuration(double seconds) => JobSummary.Duration(seconds);

    /// <summary>The options of `sweep`.</summary>
    private sealed class SweepOptions(bool focusSeries)
    {
        public JobOptions Process { get; } = new();

        public MachineOptions Machine { get; } = new();

        public Option<string?> Pattern { get; } = new("--pattern") { Description = $"What each cell burns: square (filled{(focusSeries ? string.Empty : ", the default")}), lines (every other pixel row{(focusSeries ? ", the default" : string.Empty)}), dots (every other pixel of every other row) or image (--cell-image, its larger side the cell's)" };

        public Option<string?> CellImage { get; } = new("--cell-image") { Description = "With --pattern image: the image each cell burns (any format engrave takes, dark pixels burn at 50 % threshold), its larger side spanning --cell-mm" };

        public Option<string?> FocusUm { get; } = new("--focus-um") { Description = "The focus positions, µm from the profile's visible focus (z.focusMm): FROM..TO:STEP (e.g. -200..200:50) or a list (-100,0,100)" };

        public Option<double?> CellMm { get; } = new("--cell-mm") { Description = "Side of each cell, mm (default 1)" };

        public Option<double?> SpacingMm { get; } = new("--spacing-mm") { Description = "White between cells, mm (default 0.5)" };

        public Option<double?> PitchUm { get; } = new("--pitch-um") { Description = "The cells' pixel pitch, µm, unless swept (default 50)" };

        public Option<string?> OriginMm { get; } = new("--origin-mm") { Description = "Stage position of the grid's top-left corner (its labels'), X,Y in mm (default 1,1)" };

        public Option<string?> Rows { get; } = new("--rows") { Description = "The parameter varied down the rows and its values: speed, frequency, passes, pulses-per-dot, pitch or focus (µm from the visible focus, machines with a Z axis), e.g. speed=0.5,1,2 or focus=-200..200:50" };

        public Option<string?> Columns { get; } = new("--columns") { Description = "The parameter varied across the columns and its values, e.g. frequency=500,1000,2000" };

        public Option<bool> Labels { get; } = new("--labels") { Description = "Burn each row's and column's value beside it (tiny digits, raster at the base process)" };

        public Option<int?> Passes { get; } = new("--passes") { Description = "Passes of every cell unless swept (1..100, default 1)" };

        public Option<bool> PlanOnly { get; } = new("--plan-only") { Description = "Print the grid, each cell's values, place, pulses per pixel and estimate; open nothing" };

        public Option<string?> LogDir { get; } = LogCommand.LogDirOption();

        public Option<string?> DoseDir { get; } = new("--dose-dir") { Description = "With --simulate: write each cell's pulse map (cell-rR-cC.png) into this folder" };

        public Option<string?> Dose { get; } = new("--dose") { Description = "With --simulate: write the whole sweep's pulse map (labels and cells) as one PNG, grey = pulses (black = the most)" };

        public Option<string?> Notes { get; } = new("--notes") { Description = "Notes for the sweep's log" };

        public Option<string?> Sample { get; } = new("--sample") { Description = "Sample ID for the sweep's log; also part of its file name" };

        public Option<bool> Home { get; } = new("--home") { Description = "Home both axes before the first cell even if they are homed" };

        public Option<bool> Json { get; } = new("--json") { Description = "Print one JSON object (with --plan-only: the grid; otherwise the sweep's log)" };

        public void AddTo(Command command)
        {
            Process.AddProcessTo(command);
            Machine.AddTo(command);
            foreach (var option in new Option[] { Pattern, CellImage, CellMm, SpacingMm, PitchUm, OriginMm, focusSeries ? FocusUm : Rows, Columns, Labels, Passes, PlanOnly, LogDir, DoseDir, Dose, Notes, Sample, Home, Json })
            {
                command.Options.Add(option);
            }
        }

        /// <summary>Reads the options into a sweep; throws <see cref="UsageException"/> or <see cref="SweepException"/> naming the bad value.</summary>
        public SweepSpec Bind(ParseResult result)
        {
            var profile = Process.BindProfile(result);
            var limits = MachineLimits.Of(profile);
            var rows = focusSeries
                ? result.GetValue(FocusUm) is { } focus ? SweepAxis.Parse(SweepParameter.Focus, focus, $"--focus-um {focus}") : throw new UsageException("give the focus positions: --focus-um FROM..TO:STEP, e.g. --focus-um -200..200:50")
                : SweepAxis.Parse(result.GetValue(Rows) ?? throw new UsageException("give what the rows vary: --rows PARAMETER=V1,V2,..., e.g. --rows speed=0.5,1,2"), "--rows");
            var pattern = result.GetValue(Pattern)?.Trim().ToLowerInvariant() switch
            {
                null or "" => focusSeries ? SweepPattern.Lines : SweepPattern.Square,
                "square" => SweepPattern.Square,
                "lines" => SweepPattern.Lines,
                "dots" => SweepPattern.Dots,
                "image" => SweepPattern.Image,
                var other => throw new UsageException($"--pattern {other}: use square, lines, dots or image"),
            };
            var cellImagePath = result.GetValue(CellImage);
            if ((pattern == SweepPattern.Image) != (cellImagePath is not null))
            {
                throw new UsageException(cellImagePath is null ? "--pattern image needs the cell's image: --cell-image FILE" : "--cell-image goes with --pattern image");
            }

            // Through the image loader every engraving uses: one line naming the file when it cannot be read.
            var cellImage = cellImagePath is null ? null : Core.Imaging.MaskBuilder.FromFile(cellImagePath, Core.Imaging.MaskOptions.Default, out _);
            var origin = result.GetValue(OriginMm) is { } text ? JobOptions.ParseOrigin(text) : new Core.Geometry.OriginMm(1, 1);
            OptionChecks.Refuse(new Core.Jobs.JobSettings { OriginXMm = origin.X, OriginYMm = origin.Y }, limits, Core.Jobs.JobField.OriginX, Core.Jobs.JobField.OriginY);
            return new SweepSpec
            {
                Pattern = pattern,
                CellImage = cellImage,
                CellImageName = cellImagePath is null ? null : Path.GetFileName(cellImagePath),
                CellMm = result.GetValue(CellMm) ?? 1,
                SpacingMm = result.GetValue(SpacingMm) ?? 0.5,
                PitchUm = result.GetValue(PitchUm) ?? 50,
                Origin = origin,
                Rows = rows,
                RowsOption = focusSeries ? "--focus-um" : "--rows",
                Columns = result.GetValue(Columns) is { } columns ? SweepAxis.Parse(columns, "--columns") : null,
                Labels = result.GetValue(Labels),
                Process = Process.BindProcess(result, profile),
                Plan = Process.BindPlan(result, limits),
                Profile = profile,
                Passes = result.GetValue(Passes) ?? 1,
            };
        }
    }
}

/// <summary>What `sweep --plan-only --json` prints.</summary>
internal sealed record SweepPlanSummary(int Rows, int Columns, double GridXMm, double GridYMm, double EstimatedSeconds, IReadOnlyList<SweepPlanCell> Cells)
{
    public static SweepPlanSummary From(SweepPlan plan) => new(
        plan.RowCount,
        plan.ColumnCount,
        plan.GridXMm,
        plan.GridYMm,
        plan.EstimatedSeconds,
        [.. plan.Cells.Select(c => new SweepPlanCell(c.Row, c.Column, c.Parameters, c.OriginXMm, c.OriginYMm, c.Job.Geometry.AchievedWidthMm, c.Job.Geometry.PitchUm, c.Job.Spec.Passes, c.Job.Pulses.PulsesPerPixel ?? 0, c.Job.Statistics.EngravingSeconds * c.Job.Spec.Passes, c.FocusZMicrosteps))]);
}

internal sealed record SweepPlanCell(int Row, int Column, IReadOnlyDictionary<string, double> Parameters, double OriginXMm, double OriginYMm, double SizeMm, double PitchUm, int Passes, double PulsesPerPixel, double EstimatedSeconds, long? FocusZMicrosteps);

/// <summary>What `sweep --json` prints after a run: the outcome, the log's files and the whole log.</summary>
internal sealed record SweepRunSummary(string Outcome, string? Fault, string LogPath, string SummaryPath, string? DoseDir, SweepRecord Sweep);
