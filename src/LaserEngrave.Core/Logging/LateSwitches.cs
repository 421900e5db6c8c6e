namespace LaserEngrave.Core.Logging;

/// <summary>
/// Switchings the computer sent late (docs/execution.md, "Late switchings and the edge tolerance"): switch-ons within
/// the machine profile's edge tolerance, each moving its run's entry edge that far in, and switch-offs, which cost
/// nothing since the burst had stopped the laser at the run's end by itself.
/// </summary>
/// <param name="Count">Late switch-ons sent (within the tolerance).</param>
/// <param name="LatestUm">The latest of them, µm at the burn speed (0 when none).</param>
/// <param name="ToleranceUm">The profile's edge tolerance they were judged by, µm.</param>
/// <param name="LateOffs">Late switch-offs, the burst having ended their runs by itself.</param>
public sealed record LateSwitches(int Count, double LatestUm, double ToleranceUm, int LateOffs = 0)
{
    /// <summary>Both counts together (two runs of a session, a recovery and the run it went on from).</summary>
    public static LateSwitches? Add(LateSwitches? a, LateSwitches? b) =>
        a is null ? b : b is null ? a : new LateSwitches(a.Count + b.Count, Math.Max(a.LatestUm, b.LatestUm), Math.Max(a.ToleranceUm, b.ToleranceUm), a.LateOffs + b.LateOffs);
}
