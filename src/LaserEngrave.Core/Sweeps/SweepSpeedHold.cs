using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;

namespace LaserEngrave.Core.Sweeps;

/// <summary>The speed rule of <see cref="SpeedHold"/> over a sweep's cells (here, above the jobs the cells are).</summary>
public static class SweepSpeedHold
{
    /// <summary>
    /// Null when every cell of a sweep that the host times holds; else one sentence naming the cells this computer cannot
    /// hold and the fastest speed it can: the sweep is refused before it starts, never trimmed (a grid with holes would
    /// not be the grid asked for).
    /// </summary>
    public static string? Problem(IEnumerable<SweepCell> cells, MachineProfile profile, bool scheduled)
    {
        ArgumentNullException.ThrowIfNull(cells);
        var fastest = SpeedHold.FastestMmPerS(profile, scheduled);
        var beyond = cells.Where(c => c.Job.Plan.Timing is not null && c.Job.Spec.Process.BurnSpeedMmPerS > fastest).ToList();
        if (beyond.Count == 0)
        {
            return null;
        }

        var top = beyond.Max(c => c.Job.Spec.Process.BurnSpeedMmPerS);
        // A few cells by their place; more by their speeds (the rule is the speed's alone), so the line stays one a person reads.
        var speeds = beyond.Select(c => c.Job.Spec.Process.BurnSpeedMmPerS).Distinct().Order().Select(SpeedHold.N).ToList();
        var names = beyond.Count <= 4 ? string.Join("; ", beyond.Select(c => c.Describe())) : $"every cell at {string.Join(", ", speeds)} mm/s";
        return $"{beyond.Count} {(beyond.Count == 1 ? "cell" : "cells")} of the sweep ({names}) {(beyond.Count == 1 ? "burns" : "burn")} faster than this computer can hold with this gate: {SpeedHold.Reason(top, profile)}; the fastest it holds is {SpeedHold.N(SpeedHold.Floor(fastest))} mm/s: sweep speeds up to that{SpeedHold.Instead}";
    }
}
