using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Jobs;

/// <summary>A job of several layers, each an image or a drawing with its own process, passes and mode, run in order.</summary>
public sealed class LayeredJob
{
    private LayeredJob(IReadOnlyList<JobPart> layers)
    {
        Layers = layers;

        // The layers never change and the app reads this on every render: work it out once.
        EstimatedSeconds = JobPart.RunSeconds(layers).Sum();
    }

    public IReadOnlyList<JobPart> Layers { get; }

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

        var prepared = new List<JobPart>(layers.Count);
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

    private static JobPart PrepareLayer(JobLayer layer, MachineProfile profile)
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
        var settings = JobSettings.From(process).WithMask(layer.Mask) with
        {
            ImagePath = layer.Source,
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
            return JobPart.Of(layer, job);
        }

        if (layer.Mask != Imaging.MaskOptions.Default)
        {
            throw new PlanException("thresholdPercent, dither and invert are for images");
        }

        var options = new VectorOptions
        {
            ToleranceUm = layer.ToleranceUm ?? VectorOptions.Default.ToleranceUm,
            FillPitchUm = layer.FillPitchUm ?? VectorOptions.Default.FillPitchUm,
            Fill = layer.Fill,
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
        return JobPart.Of(layer, prepared);
    }
}
