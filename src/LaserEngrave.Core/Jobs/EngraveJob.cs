using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Jobs;

/// <summary>
/// A job that can be run, of one of five kinds: <see cref="RasterJob"/>, <see cref="DotJob"/>, <see cref="DrawingJob"/>,
/// <see cref="LayersJob"/> and <c>SweepJob</c> (a job of cells, in Sweeps: a sweep is built of jobs, so it sits above them). The hierarchy is closed (the constructor is
/// private to Core), so a <c>switch</c> over it is exhaustive; the front ends and the run session take this one type
/// instead of one nullable per kind.
/// </summary>
/// <remarks>
/// Every job is a sequence of <see cref="Parts"/>, each one image or drawing with its own process and passes, run one
/// after the other (a single job has one part; a job of layers one per layer; a sweep one per cell, its labels first).
/// </remarks>
public abstract class EngraveJob
{
    private protected EngraveJob(IReadOnlyList<JobPart> parts)
    {
        if (parts.Count == 0)
        {
            throw new ArgumentException("a job has at least one part", nameof(parts));
        }

        Parts = parts;
    }

    /// <summary>The parts, in the order they run.</summary>
    public IReadOnlyList<JobPart> Parts { get; }

    /// <summary>Each part's program (<see cref="JobPart.Program"/>, built once per part), in the order they run.</summary>
    public IReadOnlyList<PartProgram> Programs => [.. Parts.Select(p => p.Program())];

    /// <summary>The (first part's) job: file, size, origin, process and machine.</summary>
    public JobSpec Spec => Parts[0].Spec;

    /// <summary>The passes of the whole job: every part's added up.</summary>
    public int Passes => Parts.Sum(p => p.Layer.Passes);

    /// <summary>What the user should know before it runs, in one line each.</summary>
    public IReadOnlyList<string> Warnings => [.. Parts.SelectMany(p => p.Warnings)];

    /// <summary>Whether every part (with its run-ups and run-outs) lies inside the stage's travel.</summary>
    public bool FitsTravel => Parts.All(p => p.FitsTravel);

    /// <summary>The whole run, every part's passes with their preflight and positioning, s.</summary>
    public virtual double EstimatedSeconds => JobPart.RunSeconds(Parts).Sum();

    /// <summary>
    /// The layers a run names in its progress ("layer 2 of 3") and a stopped run continues from
    /// (<see cref="LayerResumePoint"/>); null for a job that is not one of layers.
    /// </summary>
    public virtual IReadOnlyList<JobPart>? Layers => null;

    /// <summary>What the run counts while layer <paramref name="layer"/> (from 1, as progress reports it) runs: "stroke" for a drawing, else "row".</summary>
    public virtual string UnitOf(int layer) => Parts[0].Unit;

    /// <summary>Why the job cannot start, one line in the user's words (outside the travel, nothing to burn); null when it can.</summary>
    public virtual string? StartProblem => Parts.Select(p => p.StartProblem).FirstOrDefault(p => p is not null);

    /// <summary>What its log counts, every part's added up: rows and burn runs of an image, strokes and paths of a drawing.</summary>
    public (int Units, long Runs) Planned => (Parts.Sum(p => p.Planned.Units), Parts.Sum(p => p.Planned.Runs));

    /// <summary>The smallest pixel of its images, µm (what a laser spot much larger burns wider than it is); null without an image.</summary>
    public double? SmallestPixelUm => Parts.Select(p => p.PixelUm).Min();

    /// <summary>The image's mask a single image job burns (to tell whether the image changed since); null for any other kind.</summary>
    public Imaging.BitMask? Mask => this switch
    {
        RasterJob raster => raster.Prepared.Mask,
        DotJob dots => dots.Prepared.Mask,
        _ => null,
    };

    /// <summary>
    /// The rectangle around every part, microsteps, as Frame traces it and Job origin goes to its top-left corner; null
    /// when nothing is to be traced (a drawing without a path).
    /// </summary>
    public (long Left, long Top, long Right, long Bottom)? FrameBox
    {
        get
        {
            var boxes = Parts.Select(p => p.FrameBox).OfType<(long Left, long Top, long Right, long Bottom)>().ToList();
            return boxes.Count == 0 ? null : (boxes.Min(b => b.Left), boxes.Min(b => b.Top), boxes.Max(b => b.Right), boxes.Max(b => b.Bottom));
        }
    }

    /// <summary>
    /// Each pass's engraving with what goes before it, s, in run order: what is left of the run once a pass is under way.
    /// </summary>
    /// <param name="resumeFrom">A stopped single job goes on from here: its stopped pass only.</param>
    /// <param name="resumeLayers">A stopped job of layers goes on from here: the layers and passes done are left out.</param>
    public IReadOnlyList<double> PassSeconds(RunStopPoint? resumeFrom = null, LayerResumePoint? resumeLayers = null)
    {
        var all = Parts.SelectMany(p => Enumerable.Repeat(p.PassSeconds, p.Layer.Passes));
        return resumeLayers is { } from ? [.. all.Skip(Parts.Take(from.Layer).Sum(l => l.Layer.Passes) + from.PassesDone)]
            : resumeFrom is not null ? [.. all.Take(1)]
            : [.. all];
    }

    /// <summary>The job of one prepared image: a raster, or dots when its process is in dot mode.</summary>
    public static EngraveJob Of(PreparedJob job)
    {
        ArgumentNullException.ThrowIfNull(job);
        return job.Dots is null ? new RasterJob(job) : new DotJob(job);
    }

    /// <summary>The job of one prepared drawing.</summary>
    public static EngraveJob Of(PreparedDrawing drawing) => new DrawingJob(drawing);

    /// <summary>The job of layers.</summary>
    public static EngraveJob Of(LayeredJob layers) => new LayersJob(layers);

    // A prepared image, drawing or job of layers is a job: callers that hold one pass it where a job is taken.
    public static implicit operator EngraveJob(PreparedJob job) => Of(job);

    public static implicit operator EngraveJob(PreparedDrawing drawing) => Of(drawing);

    public static implicit operator EngraveJob(LayeredJob layers) => Of(layers);

    /// <summary>The one part a single image or drawing runs as; null for a job of layers or a sweep (a session runs those part by part).</summary>
    public virtual JobPart? SinglePart => null;

    /// <summary>The layer of a single image or drawing: named after nothing and burned its spec's passes.</summary>
    private protected static JobLayer SingleLayer(JobSpec spec, LayerMode mode) =>
        new() { Name = string.Empty, Source = spec.ImagePath, Passes = spec.Passes, Mode = mode };
}

/// <summary>An image burned row by row while the stage moves (timed switching, or step by step for a paper plan).</summary>
public sealed class RasterJob : EngraveJob
{
    internal RasterJob(PreparedJob job)
        : base([JobPart.Of(SingleLayer(job.Spec, LayerMode.Raster), job)])
    {
        Prepared = job;
    }

    public PreparedJob Prepared { get; }

    public override JobPart SinglePart => Parts[0];
}

/// <summary>An image burned as dots: the stage stops at each and the gate fires a counted burst.</summary>
public sealed class DotJob : EngraveJob
{
    internal DotJob(PreparedJob job)
        : base([JobPart.Of(SingleLayer(job.Spec, LayerMode.Raster), job)])
    {
        Prepared = job;
        Plan = job.Dots ?? throw new ArgumentException("a dot job needs a dot plan", nameof(job));
    }

    public override JobPart SinglePart => Parts[0];

    public PreparedJob Prepared { get; }

    public DotPlan Plan { get; }

    /// <summary>What runs: every dot's target and burst in device units (the part's program).</summary>
    public DotProgram Program() => ((DotPart)Parts[0]).Program();
}

/// <summary>A drawing's paths burned as strokes, each axis streaming its speed.</summary>
public sealed class DrawingJob : EngraveJob
{
    internal DrawingJob(PreparedDrawing drawing)
        : base([JobPart.Of(SingleLayer((drawing ?? throw new ArgumentNullException(nameof(drawing))).Spec, LayerMode.Outline), drawing)])
    {
        Drawing = drawing;
    }

    public override JobPart SinglePart => Parts[0];

    public PreparedDrawing Drawing { get; }

    /// <summary>What runs: per stroke the travel to it and its axis commands and laser edges in device units.</summary>
    public DrawingProgram Program() => ((DrawingPart)Parts[0]).Program();
}

/// <summary>Several images and drawings, each with its own process, passes and mode, run in order into one log.</summary>
public sealed class LayersJob : EngraveJob
{
    internal LayersJob(LayeredJob layers)
        : base((layers ?? throw new ArgumentNullException(nameof(layers))).Layers)
    {
        Layered = layers;
    }

    public LayeredJob Layered { get; }

    public override IReadOnlyList<JobPart> Layers => Parts;

    /// <summary>The unit of the layer under way; "row" outside the layers (before the first report).</summary>
    public override string UnitOf(int layer) => layer >= 1 && layer <= Parts.Count ? Parts[layer - 1].Unit : JobPart.RowUnit;

    /// <summary>A job of layers starts while every layer lies inside the travel (a layer's other problems are the Layers view's to say).</summary>
    public override string? StartProblem => FitsTravel ? null : "a layer lies outside the stage's travel: move its origin or make it smaller";

    /// <summary>The job of layers' own estimate (one homing, each later layer from where the one before ended).</summary>
    public override double EstimatedSeconds => Layered.EstimatedSeconds;
}
