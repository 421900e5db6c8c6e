using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Devices.Execution;

/// <summary>What an <see cref="EngraveSession"/> needs besides the job and the machine: the log's fields, where it goes, and how to start.</summary>
public sealed record EngraveSessionOptions
{
    public static EngraveSessionOptions Default { get; } = new();

    /// <summary>The operator's notes, for the log.</summary>
    public string? Notes { get; init; }

    /// <summary>The sample's ID, for the log (and its file name).</summary>
    public string? SampleId { get; init; }

    /// <summary>The log of the run this one repeats or continues.</summary>
    public string? RepeatOf { get; init; }

    /// <summary>Continue a stopped run from here: only the rest of the pass that stopped is run.</summary>
    public RunStopPoint? ResumeFrom { get; init; }

    /// <summary>
    /// A job of layers only: continue a stopped run of it from this layer (the earlier ones completed and are not burned
    /// again), the pass under way from its stop point, then the layer's other passes and every later layer.
    /// </summary>
    public LayerResumePoint? ResumeLayers { get; init; }

    /// <summary>A job of layers: the job file it was read from, logged with its SHA-256 so a resume can refuse a changed file.</summary>
    public string? JobFile { get; init; }

    /// <summary>Home both axes in the first pass's preflight even when they are homed.</summary>
    public bool Home { get; init; }

    /// <summary>
    /// The person accepts a laser gate without a watchdog (`--accept-no-watchdog`, the Machine panel's checkbox): without it
    /// a frequency-only profile's run is refused in preflight; with it the log keeps the sentence that was accepted.
    /// </summary>
    public bool AcceptNoWatchdog { get; init; }

    /// <summary>Where the log is written; null writes none (the result still has the record).</summary>
    public IRunLogWriter? Log { get; init; }

    /// <summary>The flight recorder of the run's links (real ports); finished and named in the log when the run ends.</summary>
    public WireRecorder? Recorder { get; init; }

    /// <summary>The image's hash for the log when the job's mask was made in memory (a sweep's cell); null: the image file's SHA-256.</summary>
    public string? ImageSha256 { get; init; }

    /// <summary>The wall clock the log's start and end times come from (the system's; a test's own).</summary>
    public TimeProvider WallClock { get; init; } = TimeProvider.System;
}
