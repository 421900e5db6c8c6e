using System.CommandLine;
using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Cli.Commands;

/// <summary>`plan --job FILE` and `engrave --job FILE`: a job of layers from a JSON file (docs/vectors.md, "Layers").</summary>
internal static class LayerCommands
{
    public static Option<string?> JobOption() =>
        new("--job") { Description = "A job of layers (JSON: images and drawings, each with its own mode, speed, frequency and passes), run in order; instead of IMAGE" };

    /// <summary>The layers of the job file, prepared; the job's own options (size, process, drawing options) are refused: each layer has its own.</summary>
    /// <param name="counter">The sample counter a mark layer numbers from; null: the app's (<see cref="MarkCommand.DefaultCounterPath"/>).</param>
    /// <param name="sample">The run's sample ID, for a mark's {sample}.</param>
    public static LayeredJob Prepare(ParseResult result, string jobFile, JobOptions job, VectorOptionSet vector, string? counter = null, string? sample = null)
    {
        RefuseJobOptions(result, "--job", job, vector, profileAllowed: true);
        var profile = result.GetValue(job.Profile) is { } path ? MachineProfile.Load(path) : MachineProfile.Default;
        var marks = new Core.Marks.JobMarks(counter ?? MarkCommand.DefaultCounterPath(), profile, DateTimeOffset.Now, sample);
        return Fitting(Named(jobFile, () => LayeredJob.Prepare(JobFile.Load(jobFile, marks), profile)), jobFile);
    }

    /// <summary>A layer's problem named with its job file, as the job file's own reading problems are.</summary>
    private static LayeredJob Named(string jobFile, Func<LayeredJob> prepare)
    {
        try
        {
            return prepare();
        }
        catch (PlanException ex) when (!ex.Message.StartsWith(jobFile, StringComparison.Ordinal))
        {
            throw new PlanException($"{jobFile}: {ex.Message}", ex) { Layer = ex.Layer };
        }
    }

    /// <summary>
    /// The layers of a logged run of layers, from its job file and with its profile, checked unchanged (SHA-256 of the
    /// file and of every layer's source); with <paramref name="resume"/>, where it goes on (docs/vectors.md, "Layers").
    /// </summary>
    public static (LayeredJob Job, string JobFile, LayerResumePoint? Resume) FromLog(ParseResult result, string log, bool resume, JobOptions job, VectorOptionSet vector)
    {
        RefuseJobOptions(result, "--from-log", job, vector, profileAllowed: false);
        var logged = RunLogStore.Read(log);
        var (layers, from) = RunReplay.ToLayers(logged, resume, log);
        MachineProfileValidator.Validate(logged.Profile, $"{log}: profile");
        return (Fitting(Named(logged.JobFile!.Path, () => LayeredJob.Prepare(layers, logged.Profile)), logged.JobFile.Path), logged.JobFile.Path, from);
    }

    /// <summary>Each layer has its own size, place, process and drawing options: the command line's are refused, naming the first.</summary>
    private static void RefuseJobOptions(ParseResult result, string with, JobOptions job, VectorOptionSet vector, bool profileAllowed)
    {
        if (result.GetValue(job.Image) is { } image)
        {
            throw new UsageException($"give IMAGE ({image}) or {with}, not both");
        }

        var given = job.Given(result).Where(name => !(profileAllowed && name == job.Profile.Name))
            .Concat(new Option[] { vector.ToleranceUm, vector.Fill, vector.FillPitchUm, vector.DrawingOrder }.Where(o => OptionChecks.IsGiven(result, o)).Select(o => o.Name));
        if (given.FirstOrDefault() is { } ignored)
        {
            throw new UsageException(with == "--job"
                ? $"{ignored} with --job: each layer of the job file has its own settings; set it there"
                : $"{ignored} with --from-log: a repeated run takes every parameter from its log and job file, so {ignored} would be ignored; leave it out");
        }
    }

    private static LayeredJob Fitting(LayeredJob layered, string jobFile)
    {
        var profile = layered.Layers[0].Spec.Profile;
        foreach (var layer in layered.Layers.Where(l => !l.FitsTravel))
        {
            throw new UsageException($"{jobFile}: layer \"{layer.Layer.Name}\" does not fit the stage's travel ({profile.X.TravelMm:0.###} x {profile.Y.TravelMm:0.###} mm); move its originMm or make it smaller");
        }

        return layered;
    }

    public static IEnumerable<string> Warnings(LayeredJob job) =>
        job.Layers.SelectMany(l => l.Warnings.Select(w => $"layer \"{l.Layer.Name}\": {w}"));

    public static int Plan(ParseResult result, LayeredJob job, bool json)
    {
        var output = result.InvocationConfiguration.Output;
        var summary = LayersSummary.From(job);
        if (json)
        {
            CliJson.Write(output, summary);
        }
        else
        {
            var c = CultureInfo.InvariantCulture;
            foreach (var (layer, i) in summary.Layers.Select((l, i) => (l, i + 1)))
            {
                output.WriteLine(string.Create(c, $"Layer {i}:          \"{layer.Name}\" {layer.Mode} {Path.GetFileName(layer.Source)}{(layer.DrawingLayer is null ? string.Empty : $" (layer {layer.DrawingLayer})")}, {layer.WidthMm:0.###} x {layer.HeightMm:0.###} mm at {layer.OriginXMm:0.###}, {layer.OriginYMm:0.###} mm"));
                output.WriteLine(string.Create(c, $"                  {layer.SpeedMmPerS:0.###} mm/s, {layer.FrequencyHz:0.###} Hz, {layer.Passes} pass(es), {RunSummaryText.Duration(layer.EstimatedSeconds)} ({layer.EstimatedSeconds:0.##} s)"));
            }

            output.WriteLine(string.Create(c, $"Estimated time:   {RunSummaryText.Duration(summary.EstimatedSeconds)} ({summary.EstimatedSeconds:0.##} s, the whole run, layers in this order); engraving {RunSummaryText.Duration(summary.EstimatedEngravingSeconds)} ({summary.EstimatedEngravingSeconds:0.##} s)"));
        }

        foreach (var warning in Warnings(job))
        {
            result.InvocationConfiguration.Error.WriteLine($"warning: {warning}");
        }

        return 0;
    }
}

/// <summary>What `plan --job FILE --json` prints: each layer and the whole job's estimate.</summary>
internal sealed record LayersSummary(IReadOnlyList<LayerSummary> Layers, double EstimatedSeconds, double EstimatedEngravingSeconds)
{
    public static LayersSummary From(LayeredJob job) => new(
        [.. job.Layers.Select(l =>
        {
            var spec = l.Spec;
            var (width, height) = l.SizeMm;
            return new LayerSummary(
                l.Layer.Name,
                l.Layer.Mode.ToString().ToLowerInvariant(),
                l.Layer.Source,
                l.Layer.DrawingLayer,
                width,
                height,
                spec.Origin.X,
                spec.Origin.Y,
                spec.Process.BurnSpeedMmPerS,
                spec.Process.LaserFrequencyHz,
                l.Layer.Passes,
                l.EstimatedSeconds,
                l.EngravingSeconds * l.Layer.Passes);
        })],
        job.EstimatedSeconds,
        job.EstimatedEngravingSeconds);
}

/// <summary>One layer in `plan --job --json`: what, where, how, and its estimate over all its passes.</summary>
internal sealed record LayerSummary(
    string Name,
    string Mode,
    string Source,
    string? DrawingLayer,
    double WidthMm,
    double HeightMm,
    double OriginXMm,
    double OriginYMm,
    double SpeedMmPerS,
    double FrequencyHz,
    int Passes,
    double EstimatedSeconds,
    double EstimatedEngravingSeconds);
