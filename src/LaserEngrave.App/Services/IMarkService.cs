using LaserEngrave.Core.Marks;
using LaserEngrave.Simulator.Marks;

namespace LaserEngrave.App.Services;

/// <summary>Makes marks into a job of layers and proves their codes on the twin (the same use case as `laserengrave mark`).</summary>
public interface IMarkService
{
    /// <summary>The sample counter's next number.</summary>
    int NextNumber();

    /// <summary>Makes <paramref name="spec"/> into a job in a folder of its own, with each code's verdict when <paramref name="check"/>.</summary>
    /// <exception cref="MarkException">The mark cannot be made as asked (one line).</exception>
    Task<MarkResult> MakeAsync(MarkSpec spec, string? sample, bool check, CancellationToken cancellationToken);
}

/// <summary>What was made: the job file (null when a code did not read), every mark, the estimate and the twin's verdicts.</summary>
public sealed record MarkResult(string? JobFile, IReadOnlyList<PlacedMark> Marks, double EstimatedSeconds, IReadOnlyList<ReadabilityVerdict> Verdicts);
