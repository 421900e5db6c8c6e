using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Jobs;

/// <summary>
/// One part of a job, ready to run: a raster (<see cref="RasterPart"/>), dots (<see cref="DotPart"/>) or a drawing
/// (<see cref="DrawingPart"/>), with the layer that asked for it. A single job has one part, a job of layers one per
/// layer, a sweep one per cell; marks are layers. The kinds are closed (the constructor is private to Core): each
/// answers every member for itself, so that no reader asks which kind it holds.
/// </summary>
public abstract class JobPart
{
    private readonly Lazy<PartProgram> _program;

    private protected JobPart(JobLayer layer)
    {
        ArgumentNullException.ThrowIfNull(layer);
        Layer = layer;

        // Built once, on first asking: the preview, the pace, the API, the estimate and every pass of a run read this one.
        _program = new Lazy<PartProgram>(BuildProgram);
    }

    /// <summary>What a run of a drawing counts: its strokes.</summary>
    public const string StrokeUnit = "stroke";

    /// <summary>What a run of an image counts: its rows.</summary>
    public const string RowUnit = "row";

    /// <summary>The layer that asked for it (for a single job: one named after nothing, burned its spec's passes).</summary>
    public JobLayer Layer { get; }

    /// <summary>The part's job: its file, size, origin, process and profile.</summary>
    public abstract JobSpec Spec { get; }

    /// <summary>
    /// The part's program, what a pass of it runs in device units: a drawing's strokes, a dot job's dots, an image's
    /// raster pass. Built once for the part's life; the preview, the estimate, the pace and the run read it.
    /// </summary>
    public PartProgram Program() => _program.Value;

    /// <summary>One pass's engraving, s.</summary>
    public abstract double EngravingSeconds { get; }

    /// <summary>The part's whole run, all its passes with their preflight and positioning, s, when it runs first (homing from the far end).</summary>
    public abstract double EstimatedSeconds { get; }

    /// <summary>What each further pass adds before its engraving: preflight without homing, the travel back to the first position, s.</summary>
    public abstract double PassSetupSeconds { get; }

    /// <summary>One pass's engraving with what goes before a further pass (preflight, the travel back), s.</summary>
    public double PassSeconds => EngravingSeconds + PassSetupSeconds;

    /// <summary>Where the part's plan starts and ends, microsteps; null for a plan without moves.</summary>
    public abstract ((long X, long Y) First, (long X, long Y) Last)? Ends { get; }

    /// <summary>Whether it (with its run-ups and run-outs) lies inside the stage's travel.</summary>
    public abstract bool FitsTravel { get; }

    /// <summary>Its size on the stage, mm (after rounding to microsteps for an image).</summary>
    public abstract (double WidthMm, double HeightMm) SizeMm { get; }

    public abstract IEnumerable<string> Warnings { get; }

    /// <summary>What a run of this part counts, as the command line and the log say it: <see cref="StrokeUnit"/> or <see cref="RowUnit"/>.</summary>
    public abstract string Unit { get; }

    /// <summary>What its log counts: an image's rows and burn runs, a drawing's strokes and the paths they burn (<see cref="Logging.RunRecord.RowsTotal"/>, <see cref="Logging.RunRecord.RunsTotal"/>).</summary>
    public abstract (int Units, long Runs) Planned { get; }

    /// <summary>What a run of it reports done one by one: an image's plan moves (a dot job's dots), a drawing's strokes.</summary>
    public abstract long Moves { get; }

    /// <summary>Its image's pixel, µm (what a laser spot much larger burns wider than it is); null for a drawing.</summary>
    public abstract double? PixelUm { get; }

    /// <summary>Why it cannot start as planned, one line in the user's words; null when it can.</summary>
    public abstract string? StartProblem { get; }

    /// <summary>Preflight's first refusal, before the speeds are checked: outside the travel, or nothing to burn; null when none.</summary>
    public abstract string? PlanProblem { get; }

    /// <summary>Preflight's refusal after the speeds: a plan the gate cannot switch (<see cref="PreparedJob.EngraveProblem"/>); null when none.</summary>
    public virtual string? EngraveProblem => null;

    /// <summary>The furthest the run takes each axis, microsteps (to hold against the axes' Maximum Position), and the microstep it counts in.</summary>
    public abstract (long Right, long Bottom, double MicrostepUm) Reach { get; }

    /// <summary>
    /// The rectangle it burns in, microsteps, as Frame traces it and Job origin goes to its top-left corner: an image's
    /// pixel grid's outer edges, the box around a drawing's planned paths; null for a drawing without a path.
    /// </summary>
    public abstract (long Left, long Top, long Right, long Bottom)? FrameBox { get; }

    /// <summary>The part of a prepared image: a raster, or dots when its process is in dot mode.</summary>
    public static JobPart Of(JobLayer layer, PreparedJob image)
    {
        ArgumentNullException.ThrowIfNull(image);
        return image.Dots is { } dots ? new DotPart(layer, image, dots) : new RasterPart(layer, image);
    }

    /// <summary>The part of a prepared drawing.</summary>
    public static JobPart Of(JobLayer layer, PreparedDrawing drawing) => new DrawingPart(layer, drawing ?? throw new ArgumentNullException(nameof(drawing)));

    /// <summary>
    /// Each part's whole run as a job of layers runs them: the first homes (<see cref="EstimatedSeconds"/>), every later
    /// one starts where the one before it ended, with the preflight of a later pass and no homing, as the executor does.
    /// </summary>
    public static IReadOnlyList<double> RunSeconds(IReadOnlyList<JobPart> parts)
    {
        ArgumentNullException.ThrowIfNull(parts);
        var seconds = new double[parts.Count];
        for (var i = 0; i < parts.Count; i++)
        {
            seconds[i] = i > 0 && parts[i - 1].Ends is { } before && parts[i].Ends is { } ends
                ? parts[i].SecondsFrom(before.Last, ends.First)
                : parts[i].EstimatedSeconds;
        }

        return seconds;
    }

    private protected abstract PartProgram BuildProgram();

    /// <summary>The preparation of a later pass from <paramref name="from"/> to <paramref name="first"/> (no homing), s.</summary>
    private protected abstract double PreparationFrom((long X, long Y) from, (long X, long Y) first);

    // The part's passes when the stage stands homed at `from`: a later pass' preflight and the travel to the first position.
    private double SecondsFrom((long X, long Y) from, (long X, long Y) first) =>
        PreparationFrom(from, first) + (Math.Max(1, Layer.Passes) * EngravingSeconds) + (Math.Max(0, Layer.Passes - 1) * PassSetupSeconds);
}

/// <summary>An image's part, burned as a raster or as dots: its mask, geometry, plan and figures.</summary>
public abstract class ImagePart : JobPart
{
    private protected ImagePart(JobLayer layer, PreparedJob image)
        : base(layer)
    {
        Image = image;
    }

    /// <summary>The prepared image: mask, geometry, plan and figures.</summary>
    public PreparedJob Image { get; }

    public override JobSpec Spec => Image.Spec;

    public override double EngravingSeconds => Image.Statistics.EngravingSeconds;

    public override double EstimatedSeconds => Image.Statistics.WholeRunSeconds(Layer.Passes);

    public override double PassSetupSeconds => Image.Statistics.PassSetupSeconds;

    public override ((long X, long Y) First, (long X, long Y) Last)? Ends => Image.Statistics.Ends;

    public override bool FitsTravel => Image.Geometry.FitsTravel;

    public override (double WidthMm, double HeightMm) SizeMm => (Image.Geometry.AchievedWidthMm, Image.Geometry.AchievedHeightMm);

    public override IEnumerable<string> Warnings => Image.Warnings.Select(w => w.Message);

    public override string Unit => RowUnit;

    public override (int Units, long Runs) Planned => (Image.Statistics.Rows, Image.Statistics.BurnRuns);

    public override long Moves => Image.Statistics.Moves;

    public override double? PixelUm => Image.Geometry.PitchUm;

    public override string? StartProblem =>
        JobRules.Placement(Image) is { } outside ? outside
        : Image.Statistics.BurnRuns == 0 ? "the mask has no pixel to burn: change the threshold or invert it"
        : null;

    public override string? PlanProblem => JobRules.Placement(Image);

    public override string? EngraveProblem => Image.EngraveProblem;

    public override (long Right, long Bottom, double MicrostepUm) Reach
    {
        get
        {
            var plan = Image.Plan;
            var geometry = plan.Geometry;
            return (Math.Min(geometry.EdgeX(geometry.WidthPx) + plan.OverscanMicrosteps, geometry.TravelXMicrosteps), geometry.EdgeY(geometry.HeightPx), geometry.MicrostepUm);
        }
    }

    public override (long Left, long Top, long Right, long Bottom)? FrameBox
    {
        get
        {
            var g = Image.Geometry.Geometry;
            return (g.EdgeX(0), g.EdgeY(0), g.EdgeX(g.WidthPx), g.EdgeY(g.HeightPx));
        }
    }

    private protected override double PreparationFrom((long X, long Y) from, (long X, long Y) first)
    {
        // The plan's own model when it has one (a dot plan keeps none): the same inputs give the same model.
        var timing = Image.Plan.Timing ?? TimedSwitching.For(Image.Spec.Process, Image.Spec.Profile, Image.Plan.Geometry.MicrostepUm);
        return timing.PreparationSeconds(first.X, first.Y, home: false, from: from);
    }
}

/// <summary>An image burned row by row while the stage moves (timed switching, or step by step for a paper plan).</summary>
public sealed class RasterPart : ImagePart
{
    internal RasterPart(JobLayer layer, PreparedJob image)
        : base(layer, image)
    {
    }

    /// <summary>The part's program (<see cref="JobPart.Program"/>), as its kind.</summary>
    public new RasterProgram Program() => (RasterProgram)base.Program();

    private protected override PartProgram BuildProgram() => Image.Program();
}

/// <summary>An image burned as dots: the stage stops at each and the gate fires a counted burst.</summary>
public sealed class DotPart : ImagePart
{
    internal DotPart(JobLayer layer, PreparedJob image, DotPlan dots)
        : base(layer, image)
    {
        Dots = dots;
    }

    /// <summary>The dot plan: what runs.</summary>
    public DotPlan Dots { get; }

    /// <summary>The part's program (<see cref="JobPart.Program"/>), as its kind.</summary>
    public new DotProgram Program() => (DotProgram)base.Program();

    private protected override PartProgram BuildProgram() => Dots.Program();
}

/// <summary>A drawing's paths burned as strokes, each axis streaming its speed.</summary>
public sealed class DrawingPart : JobPart
{
    internal DrawingPart(JobLayer layer, PreparedDrawing drawing)
        : base(layer)
    {
        Drawing = drawing;
    }

    /// <summary>The prepared drawing: its paths placed and ordered, and the strokes that burn them.</summary>
    public PreparedDrawing Drawing { get; }

    public override JobSpec Spec => Drawing.Spec;

    public override double EngravingSeconds => Drawing.Schedule.EstimatedSeconds;

    public override double EstimatedSeconds => Drawing.WholeRunSeconds(Layer.Passes);

    public override double PassSetupSeconds => Drawing.PassSetupSeconds;

    public override ((long X, long Y) First, (long X, long Y) Last)? Ends =>
        Drawing.Schedule.Strokes is { Count: > 0 } strokes ? ((strokes[0].RunUpStart.X, strokes[0].RunUpStart.Y), (strokes[^1].RestEnd.X, strokes[^1].RestEnd.Y)) : null;

    public override bool FitsTravel => Drawing.FitsTravel;

    public override (double WidthMm, double HeightMm) SizeMm => (Drawing.Plan.WidthMm, Drawing.Plan.HeightMm);

    public override IEnumerable<string> Warnings => Drawing.Warnings;

    public override string Unit => StrokeUnit;

    public override (int Units, long Runs) Planned => (Drawing.Schedule.Strokes.Count, Drawing.PathsBurned);

    public override long Moves => Drawing.Schedule.Strokes.Count;

    public override double? PixelUm => null;

    public override string? StartProblem =>
        JobRules.Placement(Drawing) is { } outside ? outside
        : Drawing.Schedule.Strokes.Count == 0 ? "the drawing has no path long enough to burn"
        : null;

    public override string? PlanProblem =>
        JobRules.Placement(Drawing) is { } outside ? outside
        : Drawing.Schedule.Strokes.Count == 0 ? $"{Drawing.Spec.ImagePath}: no path is long enough to burn"
        : null;

    /// <summary>Every stroke's run-up, path and where the axes rest after it; nothing for a drawing without a stroke.</summary>
    public override (long Right, long Bottom, double MicrostepUm) Reach
    {
        get
        {
            long right = long.MinValue, bottom = long.MinValue;
            foreach (var s in Drawing.Schedule.Strokes)
            {
                right = Math.Max(right, Math.Max(Math.Max(s.RunUpStart.X, s.RestEnd.X), s.Path.Points.Max(p => p.X)));
                bottom = Math.Max(bottom, Math.Max(Math.Max(s.RunUpStart.Y, s.RestEnd.Y), s.Path.Points.Max(p => p.Y)));
            }

            return (right, bottom, base.Program().MicrostepUm);
        }
    }

    public override (long Left, long Top, long Right, long Bottom)? FrameBox
    {
        get
        {
            var points = Drawing.Plan.Paths.SelectMany(p => p.Points).ToList();
            return points.Count == 0 ? null : (points.Min(p => p.X), points.Min(p => p.Y), points.Max(p => p.X), points.Max(p => p.Y));
        }
    }

    /// <summary>The part's program (<see cref="JobPart.Program"/>), as its kind.</summary>
    public new DrawingProgram Program() => (DrawingProgram)base.Program();

    private protected override PartProgram BuildProgram() => Drawing.Schedule.Program();

    private protected override double PreparationFrom((long X, long Y) from, (long X, long Y) first) =>
        Drawing.Schedule.Timing.PreparationSeconds(first.X, first.Y, home: false, from: from);
}
