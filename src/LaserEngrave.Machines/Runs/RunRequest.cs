using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Machines.Runs;

/// <summary>What a front end asks of a run: the job, what the log says of it, and how to start.</summary>
public sealed record RunRequest
{
    /// <summary>What runs: an image (raster or dots), a drawing or a job of layers.</summary>
    public required EngraveJob Job { get; init; }

    /// <summary>The operator's notes, for the log.</summary>
    public string? Notes { get; init; }

    /// <summary>The sample's ID, for the log (and its file name).</summary>
    public string? SampleId { get; init; }

    /// <summary>The log of the run this one repeats or continues.</summary>
    public string? RepeatOf { get; init; }

    /// <summary>Continue a stopped image job or drawing from here (the rest of its stopped pass).</summary>
    public RunStopPoint? ResumeFrom { get; init; }

    /// <summary>Continue a stopped job of layers from here (its layer and pass, then the rest).</summary>
    public LayerResumePoint? ResumeLayers { get; init; }

    /// <summary>
    /// The job file a job of layers was read from: logged with its SHA-256, its marks refused when a completed run burned
    /// their numbers already, and the sample counter advanced when this run completes (docs/marking.md).
    /// </summary>
    public string? JobFile { get; init; }

    /// <summary>Home both axes in the first pass's preflight even when they are homed.</summary>
    public bool Home { get; init; }

    /// <summary>The person accepts a laser gate without a watchdog (the log keeps the sentence accepted).</summary>
    public bool AcceptNoWatchdog { get; init; }

    /// <summary>The wall clock the log's start and end times come from.</summary>
    public TimeProvider WallClock { get; init; } = TimeProvider.System;

    /// <summary>Whether this run continues a stopped one (its marks were refused or not when it first ran, not now).</summary>
    public bool Continues => ResumeFrom is not null || ResumeLayers is not null;
}
