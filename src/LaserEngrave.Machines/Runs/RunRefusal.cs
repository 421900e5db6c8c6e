namespace LaserEngrave.Machines.Runs;

/// <summary>Why a run was refused before anything opened or moved.</summary>
public enum RunRefusalReason
{
    /// <summary>The job cannot run as planned: outside the stage's travel, or nothing to burn.</summary>
    Unrunnable,

    /// <summary>The log's folder takes no file (read-only, full, missing): a run must not start without a place for its log.</summary>
    LogNotWritable,

    /// <summary>A completed run burned the numbers of this job's marks already (two samples, one number).</summary>
    MarksBurnedAlready,
}

/// <summary>A run refused before anything opened or moved: why, and one line in a technician's words naming what is wrong.</summary>
/// <param name="Cause">The exception the check raised (the log's or the marks'), for a front end that reports it as it is; null for a job that cannot run.</param>
public sealed record RunRefusal(RunRefusalReason Reason, string Message, Exception? Cause = null);
