using LaserEngrave.Core.Jobs;

namespace LaserEngrave.Core.Sweeps;

/// <summary>A test grid: one raster or dot job per cell (the labels' first), each run and logged on its own.</summary>
public sealed class SweepJob : EngraveJob
{
    private SweepJob(SweepPlan plan)
        : base([.. plan.Jobs().Select(j => JobPart.Of(SingleLayer(j.Spec, LayerMode.Raster), j))])
    {
        Plan = plan;
        Cells = [.. plan.Jobs().Select(j => EngraveJob.Of(j))];
    }

    public SweepPlan Plan { get; }

    /// <summary>The job of a built sweep: one job per cell.</summary>
    public static SweepJob Of(SweepPlan sweep)
    {
        ArgumentNullException.ThrowIfNull(sweep);
        return new SweepJob(sweep);
    }

    /// <summary>The sweep's own estimate, focus moves between cells included.</summary>
    public override double EstimatedSeconds => Plan.EstimatedSeconds;

    /// <summary>The jobs of the labels (when there are) and of every cell, in the order they burn.</summary>
    public IReadOnlyList<EngraveJob> Cells { get; }
}
