using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Programs;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Jobs;

/// <summary>A job of several layers, each an image or a drawing with its own process, passes and mode, run in order.</summary>
public sealed class LayeredJob
{
    private LayeredJob(IReadOnlyList<PreparedLayer> layers)
    {
        Layers = layers;

        // The layers never change and the app reads this on every render: work it out once.
        EstimatedSeconds = PreparedLayer.RunSeconds(layers).Sum();
    }

    public IReadOnlyList<PreparedLayer> Layers { get; }

    /// <summary>The whole run: every layer's passes with their preflight and positioning, s.</summary>
    public double EstimatedSeconds { get; }

    /// <summary>The engraving part: every layer's engraving times its passes, s.</summary>
    public double EstimatedEngravingSeconds => Layers.Sum(l => l.EngravingSeconds * l.Layer.Passes);

    public bool FitsTravel => Layers.All(l => l.FitsTravel);

    /// <summary>Prepares every layer (reads, sizes, plans); throws one line naming the layer and the problem.</summary>
    /// <param name="layers">The layers in burn order.</param>
    /// <param name="profile">The machine: its process values fill in what a layer leaves out.</param>
    public static LayeredJob Prepare(IReadOnlyList<JobLayer> layers, MachineProfile profile)
    {
        ArgumentNullException.ThrowIfNull(layers);
        ArgumentNullException.ThrowIfNull(profile);
        if (layers.Count == 0)
        {
            throw new PlanException("a job needs at least one layer");
        }

        var prepared = new List<PreparedLayer>(layers.Count);
        foreach (var (layer, index) in layers.Select((l, i) => (l, i)))
        {
            try
            {
                prepared.Add(PrepareLayer(layer, profile));
            }
            catch (Exception ex) when (ex is GeometryException or PlanException or DrawingException or Imaging.ImageLoadException)
            {
                throw new PlanException($"layer \"{layer.Name}\": {ex.Message}", ex) { Layer = index };
            }
        }

        return new LayeredJob(prepared);
    }

    /// <summary>Where a job field stands in a job file's layer.</summary>
    private static string FileField(string field) => field switch
    {
        JobField.BurnSpeed => "speedMmPerS",
        JobField.Frequency => "frequencyHz",
        JobField.OriginX => "originMm X",
        JobField.OriginY => "originMm Y",
        _ => field,
    };

    private static PreparedLayer PrepareLayer(JobLayer layer, MachineProfile profile)
    {
        var drawing = DrawingReader.IsDrawing(layer.Source);
        if (drawing == (layer.Mode == LayerMode.Raster))
        {
            throw new PlanException(drawing
                ? $"{layer.Source} is a drawing: its mode is outline, fill or both, not raster"
                : $"{layer.Source} is an image: its mode is raster, not {layer.Mode.ToString().ToLowerInvariant()}");
        }

        var process = ProcessSettings.FromProfile(profile) with
        {
            BurnSpeedMmPerS = layer.SpeedMmPerS ?? profile.BurnSpeedMmPerS,
            LaserFrequencyHz = layer.FrequencyHz ?? profile.LaserFrequencyHz,
        };

        // The job's own rules, as the command line and the app apply them; only the names are the job file's.
        var settings = JobSettings.From(process) with
        {
            ImagePath = layer.Source,
            ThresholdPercent = layer.Mask.ThresholdPercent,
            Dither = layer.Mask.Dither,
            Invert = layer.Mask.Invert,
            QuarterTurns = layer.Mask.QuarterTurns,
            MirrorX = layer.Mask.MirrorX,
            MirrorY = layer.Mask.MirrorY,
            SizeMode = layer.WidthMm is null ? SizeMode.Height : SizeMode.Width,
            WidthMm = layer.WidthMm ?? 0,
            OriginXMm = layer.Origin.X,
            OriginYMm = layer.Origin.Y,
            Passes = layer.Passes,
            ToleranceUm = layer.ToleranceUm ?? VectorOptions.Default.ToleranceUm,
            FillPitchUm = layer.FillPitchUm ?? VectorOptions.Default.FillPitchUm,
        };
        if (JobRules.Check(settings, MachineLimits.Of(profile)) is [var problem, ..])
        {
            throw new PlanException(problem.MessageFor(FileField(problem.Field)));
        }

        if (!drawing)
        {
            if (layer.DrawingLayer is not null || layer.ToleranceUm is not null || layer.FillPitchUm is not null)
            {
                throw new PlanException("drawingLayer, toleranceUm and fillPitchUm are for drawings");
            }

            if (!Enum.IsDefined(layer.Mask.Dither))
            {
                throw new PlanException($"dither {layer.Mask.Dither} is not one of the known");
            }

            var width = layer.WidthMm ?? throw new PlanException($"{layer.Source}: an image layer needs widthMm");
            var job = PreparedJob.Prepare(new JobSpec
            {
                ImagePath = layer.Source,
                Mask = layer.Mask,
                Size = SizeSpec.Width(width),
                Origin = layer.Origin,
                Process = process,
                Profile = profile,
                Passes = layer.Passes,
            });
            return new PreparedLayer(layer, job, null);
        }

        if (layer.Mask != Imaging.MaskOptions.Default)
        {
            throw new PlanException("thresholdPercent, dither and invert are for images");
        }

        var options = new VectorOptions
        {
            ToleranceUm = layer.ToleranceUm ?? VectorOptions.Default.ToleranceUm,
            FillPitchUm = layer.FillPitchUm ?? VectorOptions.Default.FillPitchUm,
            Fill = layer.Mode switch
            {
                LayerMode.Fill => VectorFillMode.Fill,
                LayerMode.Both => VectorFillMode.Both,
                _ => VectorFillMode.Outline,
            },
            Layer = layer.DrawingLayer,
        };
        var spec = new JobSpec
        {
            ImagePath = layer.Source,
            Size = SizeSpec.Width(layer.WidthMm ?? 1),
            Origin = layer.Origin,
            Process = process,
            Profile = profile,
            Passes = layer.Passes,

            // The layer's turn and mirrors, as for an image layer.
            Mask = layer.Mask,
        };
        var prepared = layer.WidthMm is null ? PreparedDrawing.PrepareOwnSize(spec, options) : PreparedDrawing.Prepare(spec, options);
        return new PreparedLayer(layer, null, prepared);
    }
}

/// <summary>One layer ready to run: an image job or a drawing, with the layer that asked for it.</summary>
public sealed record PreparedLayer(JobLayer Layer, PreparedJob? Image, PreparedDrawing? Drawing)
{
    /// <summary>One pass's engraving, s.</summary>
    public double EngravingSeconds => Image?.Statistics.EngravingSeconds ?? Drawing!.Schedule.EstimatedSeconds;

    /// <summary>The layer's whole run, all its passes with their preflight and positioning, s, when it runs first (homing from the far end).</summary>
    public double EstimatedSeconds => Image?.Statistics.WholeRunSeconds(Layer.Passes) ?? Drawing!.WholeRunSeconds(Layer.Passes);

    /// <summary>Where the layer's plan starts and ends, microsteps; null for a plan without moves.</summary>
    public ((long X, long Y) First, (long X, long Y) Last)? Ends =>
        Image is { } image ? image.Statistics.Ends
        : Drawing!.Schedule.Strokes is { Count: > 0 } strokes ? ((strokes[0].RunUpStart.X, strokes[0].RunUpStart.Y), (strokes[^1].RestEnd.X, strokes[^1].RestEnd.Y))
        : null;

    /// <summary>
    /// Each layer's whole run as a job of layers runs them: the first homes (<see cref="EstimatedSeconds"/>), every later
    /// one starts where the one before it ended, with the preflight of a later pass and no homing, as the executor does.
    /// </summary>
    public static IReadOnlyList<double> RunSeconds(IReadOnlyList<PreparedLayer> layers)
    {
        ArgumentNullException.ThrowIfNull(layers);
        var seconds = new double[layers.Count];
        for (var i = 0; i < layers.Count; i++)
        {
            seconds[i] = i > 0 && layers[i - 1].Ends is { } before && layers[i].Ends is not null
                ? layers[i].SecondsFrom(before.Last)
                : layers[i].EstimatedSeconds;
        }

        return seconds;
    }

    // The layer's passes when the stage stands homed at `from`: a later pass' preflight and the travel to the first position.
    private double SecondsFrom((long X, long Y) from)
    {
        var first = Ends!.Value.First;
        if (Image is { } image)
        {
            // The plan's own model when it has one (a dot plan keeps none): the same inputs give the same model.
            var timing = image.Plan.Timing ?? TimedSwitching.For(image.Spec.Process, image.Spec.Profile, image.Plan.Geometry.MicrostepUm);
            var statistics = image.Statistics;
            return timing.PreparationSeconds(first.X, first.Y, home: false, from: from)
                + (Math.Max(1, Layer.Passes) * statistics.EngravingSeconds) + (Math.Max(0, Layer.Passes - 1) * statistics.PassSetupSeconds);
        }

        var drawing = Drawing!;
        return drawing.Schedule.Timing.PreparationSeconds(first.X, first.Y, home: false, from: from)
            + (Math.Max(1, Layer.Passes) * drawing.Schedule.EstimatedSeconds) + (Math.Max(0, Layer.Passes - 1) * drawing.PassSetupSeconds);
    }

    public bool FitsTravel => Image?.Geometry.FitsTravel ?? Drawing!.FitsTravel;

    /// <summary>
    /// The part's program, what a pass of it runs in device units: a drawing's strokes, a dot job's dots, an image's
    /// raster pass. The one place a part's kind chooses its program; the preview, the estimate and the run read it.
    /// </summary>
    public PartProgram Program() => Drawing is { } drawing ? drawing.Schedule.Program()
        : Image!.Dots is { } dots ? dots.Program()
        : Image.Program();

    /// <summary>The layer's job: its file, size, origin, process and profile.</summary>
    public JobSpec Spec => Image?.Spec ?? Drawing!.Spec;

    /// <summary>Its size on the stage, mm (after rounding to microsteps for an image).</summary>
    public (double WidthMm, double HeightMm) SizeMm =>
        Image is { } image ? (image.Geometry.AchievedWidthMm, image.Geometry.AchievedHeightMm) : (Drawing!.Plan.WidthMm, Drawing.Plan.HeightMm);

    public IEnumerable<string> Warnings => Image?.Warnings.Select(w => w.Message) ?? Drawing!.Warnings;

    /// <summary>What a run of a drawing counts: its strokes.</summary>
    public const string StrokeUnit = "stroke";

    /// <summary>What a run of an image counts: its rows.</summary>
    public const string RowUnit = "row";

    /// <summary>What a run of this part counts, as the command line and the log say it: <see cref="StrokeUnit"/> for a drawing, else <see cref="RowUnit"/>.</summary>
    public string Unit => Drawing is null ? RowUnit : StrokeUnit;

    /// <summary>One pass's engraving with what goes before a further pass (preflight, the travel back), s.</summary>
    public double PassSeconds => EngravingSeconds + (Image?.Statistics.PassSetupSeconds ?? Drawing!.PassSetupSeconds);

    /// <summary>What its log counts: an image's rows and burn runs, a drawing's strokes and the paths they burn (<see cref="Logging.RunRecord.RowsTotal"/>, <see cref="Logging.RunRecord.RunsTotal"/>).</summary>
    public (int Units, long Runs) Planned => Image is { } image
        ? (image.Statistics.Rows, image.Statistics.BurnRuns)
        : (Drawing!.Schedule.Strokes.Count, Drawing.PathsBurned);

    /// <summary>Why it cannot start as planned, one line in the user's words; null when it can.</summary>
    public string? StartProblem => Image is { } image
        ? !image.Geometry.FitsTravel ? "the job lies outside the stage's travel: move the origin or make it smaller"
            : image.Statistics.BurnRuns == 0 ? "the mask has no pixel to burn: change the threshold or invert it"
            : null
        : !Drawing!.FitsTravel ? "the drawing lies outside the stage's travel: move the origin or make it smaller"
            : Drawing.Schedule.Strokes.Count == 0 ? "the drawing has no path long enough to burn"
            : null;

    /// <summary>
    /// The rectangle it burns in, microsteps, as Frame traces it and Job origin goes to its top-left corner: an image's
    /// pixel grid's outer edges, the box around a drawing's planned paths; null for a drawing without a path.
    /// </summary>
    public (long Left, long Top, long Right, long Bottom)? FrameBox
    {
        get
        {
            if (Image is { } image)
            {
                var g = image.Geometry.Geometry;
                return (g.EdgeX(0), g.EdgeY(0), g.EdgeX(g.WidthPx), g.EdgeY(g.HeightPx));
            }

            var points = Drawing!.Plan.Paths.SelectMany(p => p.Points).ToList();
            return points.Count == 0 ? null : (points.Min(p => p.X), points.Min(p => p.Y), points.Max(p => p.X), points.Max(p => p.Y));
        }
    }
}
