using System.CommandLine;
using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Cli.Commands;

/// <summary>`laserengrave plan IMAGE (size) ...`: the raster plan's figures, and optionally every move as CSV.</summary>
internal static class PlanCommand
{
    public static Command Create()
    {
        var job = new JobOptions();
        var json = new Option<bool>("--json")
        {
            Description = "Print one JSON object; estimatedSeconds is the whole run (preflight, homing from the far end, the first travel and the engraving), estimatedEngravingSeconds the engraving alone",
        };
        var segments = new Option<string?>("--segments") { Description = "Write every move in order as CSV (kind,x0,y0,x1,y1 in microsteps)" };
        var vector = new VectorOptionSet();
        var jobFile = LayerCommands.JobOption();
        job.Image.Arity = ArgumentArity.ZeroOrOne;
        var command = new Command("plan", "Size an image on the stage and plan the raster: runs, lengths, laser switches, the estimated time of the whole run; or a drawing (.dxf, .svg): paths, lengths, strokes, estimated time; or a job of layers (--job)");
        job.AddTo(command);
        vector.AddTo(command);
        command.Options.Add(json);
        command.Options.Add(segments);
        command.Options.Add(jobFile);
        command.SetAction(result =>
        {
            if (result.GetValue(jobFile) is { } file)
            {
                if (result.GetValue(segments) is not null)
                {
                    throw new UsageException("--segments is for one image or drawing, not a job of layers");
                }

                return LayerCommands.Plan(result, LayerCommands.Prepare(result, file, job, vector), result.GetValue(json));
            }

            if (result.GetValue(job.Image) is null)
            {
                throw new UsageException("IMAGE (or --job FILE) is required");
            }

            if (VectorCommands.IsDrawing(result, job))
            {
                return VectorCommands.Plan(result, job, vector, result.GetValue(json), result.GetValue(segments));
            }

            OptionChecks.OutputFile(result.GetValue(segments), "--segments");
            var prepared = PreparedJob.Prepare(job.Bind(result));
            if (result.GetValue(segments) is { } csv)
            {
                MoveCsvWriter.Write(prepared.Plan, csv);
            }

            var output = result.InvocationConfiguration.Output;
            if (result.GetValue(json))
            {
                CliJson.Write(output, JobSummary.From(prepared));
            }
            else
            {
                JobSummary.WriteText(output, prepared);
            }

            foreach (var warning in prepared.Warnings)
            {
                result.InvocationConfiguration.Error.WriteLine($"warning: {warning.Message}");
            }

            return 0;
        });
        return command;
    }
}

/// <summary>The figures of a prepared job, as `plan --json` prints them.</summary>
internal sealed record JobSummary(
    string Image,
    int WidthPx,
    int HeightPx,
    double PitchUm,
    double MicrostepsPerPixel,
    double WidthMm,
    double HeightMm,
    double OriginXMm,
    double OriginYMm,
    double ResidualScaleError,
    bool FitsTravel,
    string Strategy,
    bool Bidirectional,
    double OverscanMm,
    double ScanOffsetUm,
    int Rows,
    long Moves,
    long BurnRuns,
    double BurnLengthMm,
    double TravelLengthMm,
    long LaserSwitches,
    int Passes,
    double EstimatedSeconds,
    double EstimatedEngravingSeconds,
    double EstimatedPreparationSeconds,
    double LowerBoundSeconds,
    IReadOnlyList<string> Warnings,
    double PulseSpacingUm,
    double OverlapPercent,
    double PulsesPerPixel,
    string Mode,
    int PulsesPerDot,
    long? DotPitchMicrosteps,
    double? DotSpacingUm,
    long? Dots)
{
    public static JobSummary From(PreparedJob job)
    {
        var g = job.Geometry;
        var s = job.Statistics;
        return new JobSummary(
            job.Spec.ImagePath,
            job.Mask.Width,
            job.Mask.Height,
            g.PitchUm,
            g.MicrostepsPerPixel,
            g.AchievedWidthMm,
            g.AchievedHeightMm,
            job.Spec.Origin.X,
            job.Spec.Origin.Y,
            g.ResidualScaleError,
            g.FitsTravel,
            job.Spec.Plan.Strategy.ToString().ToLowerInvariant(),
            job.Spec.Plan.Bidirectional,
            job.Spec.Plan.OverscanMm,
            job.Plan.ScanOffsetUm,
            s.Rows,
            s.Moves,
            s.BurnRuns,
            s.BurnLengthMm,
            s.TravelLengthMm,
            s.LaserSwitches,
            job.Spec.Passes,
            s.WholeRunSeconds(job.Spec.Passes),
            s.EngravingSeconds * job.Spec.Passes,
            s.PreparationSeconds,
            s.LowerBoundSeconds,
            [.. job.Warnings.Select(w => w.Message)],
            job.Pulses.PulseSpacingUm,
            job.Pulses.OverlapPercent,
            job.Pulses.PulsesPerPixel ?? 0,
            job.Spec.Process.Mode == PlanMode.Dots ? "dots" : "raster",
            job.Spec.Process.PulsesPerDot,
            job.Dots?.DotPitchMicrosteps,
            job.Dots?.DotSpacingUm,
            job.Dots?.Estimate.Dots);
    }

    public static void WriteText(TextWriter output, PreparedJob job)
    {
        var s = From(job);
        var c = CultureInfo.InvariantCulture;
        output.WriteLine(string.Create(c, $"Image:            {s.Image} ({s.WidthPx} x {s.HeightPx} px)"));
        output.WriteLine(string.Create(c, $"Size on stage:    {s.WidthMm:0.####} x {s.HeightMm:0.####} mm at origin {s.OriginXMm:0.###}, {s.OriginYMm:0.###} mm"));
        output.WriteLine(string.Create(c, $"Pitch:            {s.PitchUm:0.####} µm = {s.MicrostepsPerPixel:0.####} microsteps per pixel"));
        output.WriteLine(string.Create(c, $"Scale error:      {s.ResidualScaleError * 1e6:0.##} ppm after rounding to microsteps"));
        output.WriteLine(string.Create(c, $"Fits the travel:  {(s.FitsTravel ? "yes" : "NO")}"));
        if (job.Spec.Profile.Calibration is { } calibration)
        {
            output.WriteLine($"Compensated:      {calibration.Describe()} (the profile's calibration)");
        }

        output.WriteLine(string.Create(c, $"Strategy:         {s.Strategy}{(s.Strategy == "optimized" ? $", {(s.Bidirectional ? "bidirectional" : "unidirectional")}, overscan {s.OverscanMm:0.###} mm" : string.Empty)}{(s.ScanOffsetUm != 0 && s.Strategy == "optimized" && s.Bidirectional ? $", right-to-left rows shifted {s.ScanOffsetUm:0.###} µm (the profile's scanOffsets)" : string.Empty)}"));
        if (job.Dots is { } dots)
        {
            output.WriteLine(string.Create(c, $"Mode:             dots, {dots.PulsesPerDot} pulses at {job.Spec.Process.LaserFrequencyWholeHz} Hz per dot, a dot at {dots.DescribePitch()}, {dots.Estimate.Dots} dots ({dots.Estimate.Pulses} pulses)"));
            output.WriteLine(string.Create(c, $"Per dot:          {Units.SecondsToMs(dots.Estimate.AtDotSeconds):0.##} ms standing (settle {Units.SecondsToMs(dots.Estimate.SettleSeconds):0.##} ms, burst {Units.SecondsToMs(dots.Estimate.BurstSeconds):0.##} ms, commands and the wait for its end), steps {dots.Estimate.StepsSeconds:0.##} s in all"));
        }

        output.WriteLine(string.Create(c, $"Rows:             {s.Rows}"));
        output.WriteLine(string.Create(c, $"Moves:            {s.Moves}"));
        output.WriteLine(string.Create(c, $"Burn runs:        {s.BurnRuns} ({s.BurnLengthMm:0.###} mm)"));
        output.WriteLine(string.Create(c, $"Travel:           {s.TravelLengthMm:0.###} mm"));
        output.WriteLine(string.Create(c, $"Laser switches:   {s.LaserSwitches}"));
        output.WriteLine(string.Create(c, $"Pulses:           {s.PulseSpacingUm:0.###} µm apart, {s.OverlapPercent:0.#} % overlap, {s.PulsesPerPixel:0.##} per pixel"));
        output.WriteLine(string.Create(c, $"Estimated time:   {Duration(s.EstimatedSeconds)} for the whole run{(s.Passes > 1 ? $" of {s.Passes} passes" : string.Empty)}: preflight, homing from the far end and the first travel {Duration(s.EstimatedPreparationSeconds)}, engraving {Duration(s.EstimatedEngravingSeconds)}"));
        if (job.Dots is null)
        {
            output.WriteLine(string.Create(c, $"Lower bound:      {Duration(s.LowerBoundSeconds)} (motion only)"));
        }
    }

    public static string Duration(double seconds)
    {
        var t = TimeSpan.FromSeconds(Math.Round(seconds));
        return t.TotalHours >= 1
            ? string.Create(CultureInfo.InvariantCulture, $"{(int)t.TotalHours} h {t.Minutes:00} min {t.Seconds:00} s")
            : string.Create(CultureInfo.InvariantCulture, $"{t.Minutes} min {t.Seconds:00} s ({seconds:0.0} s)");
    }
}
