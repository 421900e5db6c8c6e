using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Marks;
using LaserEngrave.Simulator.Marks;

namespace LaserEngrave.Machines.Marks;

/// <summary>What <see cref="MarkMaking"/> made: the layout, the planned job, the job file (null when a code did not read) and the twin's verdicts.</summary>
public sealed record MadeMarks(MarkLayout Layout, LayeredJob Job, string? JobFile, IReadOnlyList<ReadabilityVerdict> Verdicts, double? SmallestReadableModuleUm)
{
    /// <summary>The first code that did not read on the twin, if any.</summary>
    public ReadabilityVerdict? Unreadable => Verdicts.FirstOrDefault(v => !v.Reads);
}
