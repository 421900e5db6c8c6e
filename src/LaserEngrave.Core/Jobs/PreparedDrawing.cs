using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Jobs;

/// <summary>A drawing ready to preview, estimate or engrave: its paths placed and ordered, and the strokes that burn them.</summary>
public sealed class PreparedDrawing
{
    private PreparedDrawing(JobSpec spec, VectorOptions vector, VectorPlan plan, VectorSchedule schedule)
    {
        Spec = spec;
        Vector = vector;
        Plan = plan;
        Schedule = schedule;
    }

    /// <summary>The job: <see cref="JobSpec.ImagePath"/> is the drawing, its size by width (as asked, or the drawing's own).</summary>
    public JobSpec Spec { get; }

    public VectorOptions Vector { get; }

    public VectorPlan Plan { get; }

    public VectorSchedule Schedule { get; }

    /// <summary>What a run adds before its engraving: preflight, homing from the far end, the travel to the first run-up, s.</summary>
    public double PreparationSeconds
    {
        get
        {
            var first = Schedule.Strokes.Count > 0 ? Schedule.Strokes[0].RunUpStart : Plan.Start;
            return Schedule.Timing.PreparationSeconds(first.X, first.Y, home: true, from: (0, 0));
        }
    }

    /// <summary>What each further pass adds before its engraving: preflight without homing, the travel back to the first run-up, s.</summary>
    public double PassSetupSeconds
    {
        get
        {
            var first = Schedule.Strokes.Count > 0 ? Schedule.Strokes[0].RunUpStart : Plan.Start;
            var last = Schedule.Strokes.Count > 0 ? Schedule.Strokes[^1].RestEnd : Plan.Start;
            return Schedule.Timing.PreparationSeconds(first.X, first.Y, home: false, from: (last.X, last.Y));
        }
    }

    /// <summary>The whole run of <paramref name="passes"/> passes, as for images (<c>PlanStatistics.WholeRunSeconds</c>), s.</summary>
    public double WholeRunSeconds(int passes = 1) =>
        PreparationSeconds + (Math.Max(1, passes) * Schedule.EstimatedSeconds) + (Math.Max(0, passes - 1) * PassSetupSeconds);

    /// <summary>
    /// How many of the drawing's paths its strokes burn (a path cut into several strokes counts once): the drawing's burn
    /// runs to do, as the run's progress, its stop point, Continue and the log all count them. A path too short to switch
    /// the laser on and off is not burned, so it is not counted (the plan's warnings name it).
    /// </summary>
    public int PathsBurned => Schedule.Strokes.Select(s => s.PathIndex).Distinct().Count();

    /// <summary>Whether the paths and every stroke's run-up and run-out stay inside the travel.</summary>
    public bool FitsTravel => Plan.FitsTravel && Schedule.FitsTravel;

    /// <summary>The drawing's warnings (what was skipped), then the motion's.</summary>
    public IReadOnlyList<string> Warnings => [.. Plan.Warnings, .. Schedule.Warnings];

    /// <summary>Reads, places, orders and plans the strokes of the drawing at <see cref="JobSpec.ImagePath"/>; throws one-line typed errors.</summary>
    /// <param name="spec">The job; its <see cref="JobSpec.Size"/> is by width (or, for a drawing with no width, its own height).</param>
    /// <param name="vector">Tolerance, fill and order; its width and origin are taken from <paramref name="spec"/>.</param>
    /// <param name="motion">How paths become strokes; the defaults when null.</param>
    public static PreparedDrawing Prepare(JobSpec spec, VectorOptions vector, VectorMotionOptions? motion = null)
    {
        ArgumentNullException.ThrowIfNull(spec);
        ArgumentNullException.ThrowIfNull(vector);
        JobRules.Require(spec.Process, spec.Profile);
        vector = Oriented(spec, vector);
        var plan = spec.Size switch
        {
            SizeSpec.ByWidth w => VectorPlanner.Plan(spec.ImagePath, vector with { WidthMm = w.WidthMm, Origin = spec.Origin }, spec.Profile),
            SizeSpec.ByHeight h => OwnHeight(spec, vector, h.HeightMm),
            _ => throw new GeometryException($"{spec.ImagePath}: a drawing is sized by its width ({spec.Size.Describe()} was asked)"),
        };
        return Build(spec, vector with { WidthMm = plan.WidthMm, Origin = spec.Origin }, plan, motion);
    }

    /// <summary>As <see cref="Prepare(JobSpec, VectorOptions, VectorMotionOptions?)"/> with the drawing's own size (its units); the size is recorded in the spec.</summary>
    public static PreparedDrawing PrepareOwnSize(JobSpec spec, VectorOptions vector, VectorMotionOptions? motion = null)
    {
        ArgumentNullException.ThrowIfNull(spec);
        ArgumentNullException.ThrowIfNull(vector);
        JobRules.Require(spec.Process, spec.Profile);
        vector = Oriented(spec, vector);
        var plan = VectorPlanner.Plan(spec.ImagePath, vector with { WidthMm = null, Origin = spec.Origin }, spec.Profile);

        // A drawing with no width (one vertical line) is recorded by its height, so a repeat finds the same size.
        var size = plan.WidthMm > 0 ? SizeSpec.Width(plan.WidthMm) : SizeSpec.Height(plan.HeightMm);
        return Build(spec with { Size = size }, vector with { WidthMm = null, Origin = spec.Origin }, plan, motion);
    }

    /// <summary>The job's turn and mirrors (its spec's, where an image's are too) given to the drawing's plan: the one place a drawing takes them.</summary>
    private static VectorOptions Oriented(JobSpec spec, VectorOptions vector) =>
        vector with { QuarterTurns = spec.Mask.QuarterTurns, MirrorX = spec.Mask.MirrorX, MirrorY = spec.Mask.MirrorY };

    private static VectorPlan OwnHeight(JobSpec spec, VectorOptions vector, double heightMm)
    {
        var plan = VectorPlanner.Plan(spec.ImagePath, vector with { WidthMm = null, Origin = spec.Origin }, spec.Profile);
        return Math.Abs(plan.HeightMm - heightMm) <= 1e-9 * Math.Max(1, heightMm)
            ? plan
            : throw new GeometryException($"{spec.ImagePath}: a drawing is sized by its width, or keeps its own size ({plan.HeightMm} mm high)");
    }

    private static PreparedDrawing Build(JobSpec spec, VectorOptions vector, VectorPlan plan, VectorMotionOptions? motion)
    {
        var timing = TimedSwitching.For(spec.Process, spec.Profile, plan.MicrostepUm);
        var schedule = VectorMotion.Plan(plan, timing, spec.Profile, motion);
        return new PreparedDrawing(spec, vector, plan, schedule);
    }
}
