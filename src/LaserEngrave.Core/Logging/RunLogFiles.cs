namespace LaserEngrave.Core.Logging;

/// <summary>The two files a run's log was written to: the JSON record and the text summary beside it.</summary>
public sealed record RunLogFiles(string JsonPath, string TextPath)
{
    /// <summary>
    /// Why the log is not in the folder asked for (that folder's one-line error), when <see cref="FallbackRunLogWriter"/>
    /// wrote it to a fallback folder instead; null when it is where it was asked to be.
    /// </summary>
    public string? FallbackReason { get; init; }

    /// <summary>The one line that says where the log went instead and why, for the front end to show first; null when it is where it was asked to be.</summary>
    public string? Notice => FallbackReason is null ? null : $"the run log is in {JsonPath} instead: {FallbackReason}";
}
