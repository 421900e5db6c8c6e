using LaserEngrave.Core.Marks;

namespace LaserEngrave.Core.Logging;

/// <summary>The job file of a run of layers (`engrave --job`): where it was and its SHA-256, so a resume can refuse a changed job.</summary>
public sealed record RunJobFile(string Path, string Sha256)
{
    /// <summary>The job's marks: the counter, the numbers the run burns and when they were made; null for a job without marks.</summary>
    public RunJobMarks? Marks { get; init; }
}

/// <summary>
/// The numbers a run of marks burns: a completed run advances <paramref name="Counter"/> past them, and a resumed run
/// makes its job file's marks again from <paramref name="FirstNumber"/> and <paramref name="MadeAt"/>, so it keeps them.
/// </summary>
/// <param name="Counter">The sample counter's file.</param>
/// <param name="FirstNumber">The first copy's number.</param>
/// <param name="Count">How many numbers the run burns.</param>
/// <param name="MadeAt">When a job file's marks were made ({date}, {time}); null for a job that `mark` made (its files are fixed).</param>
public sealed record RunJobMarks(string Counter, int FirstNumber, int Count, DateTimeOffset? MadeAt)
{
    /// <summary>The marks' record beside <paramref name="jobFile"/> as a run's log carries it; null when the job has no marks.</summary>
    public static RunJobMarks? Beside(string jobFile) =>
        MarkManifest.Beside(jobFile) is { } manifest ? new RunJobMarks(manifest.Counter, manifest.FirstNumber, manifest.Count, manifest.MadeAt) : null;
}
