using System.Globalization;

namespace LaserEngrave.Core.Planning;

/// <summary>How to plan a raster: strategy, scan direction and overscan.</summary>
public sealed record PlanOptions
{
    public static PlanOptions Default { get; } = new();

    public PlanStrategy Strategy { get; init; } = PlanStrategy.Optimized;

    /// <summary>Serpentine rows (alternate direction on every visited row); <see cref="PlanStrategy.Optimized"/> only.</summary>
    public bool Bidirectional { get; init; } = true;

    /// <summary>
    /// Run-up before and run-out after each burn run, mm, laser off at the burn speed, so the laser burns at constant
    /// speed; <see cref="PlanStrategy.Optimized"/> only. Shortened where it would leave the stage's travel.
    /// </summary>
    public double OverscanMm { get; init; }

    /// <summary>Throws a <see cref="PlanException"/> naming the first unusable value.</summary>
    public void Validate()
    {
        if (!Enum.IsDefined(Strategy))
        {
            throw new PlanException($"strategy {Strategy} is not known (paper or optimized)");
        }

        if (!(OverscanMm >= 0) || double.IsInfinity(OverscanMm))
        {
            throw new PlanException($"overscan {OverscanMm.ToString(CultureInfo.InvariantCulture)} mm must be a finite number of 0 or more");
        }
    }
}
