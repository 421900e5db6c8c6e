using System.Reflection;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Logging;

/// <summary>One engraving run, completed or not: everything needed to cite it in a lab notebook and to repeat it.</summary>
/// <remarks>
/// Saved as JSON by <see cref="RunLogStore"/> with <see cref="SchemaVersion"/>; docs/run-log.md describes every field.
/// Times are the wall clock with its offset, except that on the simulator the durations are virtual time.
/// </remarks>
public sealed record RunRecord
{
    /// <summary>The schema version this build writes; it reads this one and older (<see cref="RunLogMigration"/>).</summary>
    /// <remarks>2: every member written (version 1 logs lack the members added during its life); 3: the gate's kind, scheduled
    /// burst and capabilities, and the camera (docs/run-log.md, "Older logs").</remarks>
    public const int CurrentSchemaVersion = 3;

    public int SchemaVersion { get; init; } = CurrentSchemaVersion;

    /// <summary>
    /// The schema version the file was written with, when it was older than <see cref="CurrentSchemaVersion"/> and
    /// migrated on reading (<see cref="RunLogMigration"/>); not written. A version 1 stop point may count moves of an
    /// older plan (<see cref="RunReplay.StopPointInPlan"/>).
    /// </summary>
    [System.Text.Json.Serialization.JsonIgnore]
    public int ReadFromSchemaVersion { get; init; } = CurrentSchemaVersion;

    /// <summary>LaserEngrave's version that ran the job.</summary>
    public required string SoftwareVersion { get; init; }

    /// <summary>When the run started (before preflight), with the local offset.</summary>
    public required DateTimeOffset StartedAt { get; init; }

    /// <summary>When the run ended, laser off, with the local offset.</summary>
    public required DateTimeOffset EndedAt { get; init; }

    public required RunOutcome Outcome { get; init; }

    /// <summary>What stopped the run; null when it completed.</summary>
    public RunFault? Fault { get; init; }

    /// <summary>Where it stopped (the first move not completed); null when it completed.</summary>
    public RunStopPoint? StoppedAt { get; init; }

    public required RunImage Image { get; init; }

    public required MaskOptions Mask { get; init; }

    public required RunGeometry Geometry { get; init; }

    /// <summary>Strategy, direction and overscan.</summary>
    public required PlanOptions Plan { get; init; }

    /// <summary>Burn and travel speeds, acceleration, laser frequency and baud rates.</summary>
    public required ProcessSettings Process { get; init; }

    public required MachineProfile Profile { get; init; }

    /// <summary>Whether the run was on the built-in simulator (durations then are virtual time).</summary>
    public bool Simulated { get; init; }

    /// <summary>
    /// The host's CPU priority during a run on real ports ("raised (...)" or "normal (...)" with the reason); null on the
    /// built-in simulator. Timed switching plans to the millisecond, and a computer busy with other work can delay it.
    /// </summary>
    public string? HostPriority { get; init; }

    /// <summary>The devices as they identified themselves, with their firmware versions.</summary>
    public IReadOnlyList<RunDevice> Devices { get; init; } = [];

    /// <summary>
    /// The estimated duration of the whole run, s: preflight, homing, the travel to the first move and the engraving of
    /// every pass (all of the plan, or what follows a resume point). Compare with <see cref="ActualSeconds"/>.
    /// </summary>
    public required double EstimatedSeconds { get; init; }

    /// <summary>The part of <see cref="EstimatedSeconds"/> that is engraving, s. Compare with <see cref="EngravingSeconds"/>.</summary>
    public double EstimatedEngravingSeconds { get; init; }

    /// <summary>How long the run took from start to end, s (virtual when simulated).</summary>
    public double ActualSeconds { get; init; }

    /// <summary>The part of <see cref="ActualSeconds"/> the estimate models (from the first move of the plan to the end, pauses left out), s.</summary>
    public double EngravingSeconds { get; init; }

    /// <summary>How long the laser was on, s.</summary>
    public double LaserOnSeconds { get; init; }

    /// <summary>Switchings sent late but within the profile's edge tolerance; null when none was (and in older logs).</summary>
    public LateSwitches? LateSwitches { get; init; }

    /// <summary>
    /// How many times the profile's latency spread the run's guards assumed, when more than the profile's (a loaded
    /// computer, or a check that found the latencies spread wider): every switching was aimed that much further inside its
    /// run, so lines came out shorter; null when the profile's held (and in older logs).
    /// </summary>
    public double? GuardScale { get; init; }

    public int RowsDone { get; init; }

    /// <summary>What <see cref="RowsDone"/> and <see cref="RowsTotal"/> count, as the log's reader says it: "strokes" for a drawing, else "rows" (not written: the log's kind says it).</summary>
    [System.Text.Json.Serialization.JsonIgnore]
    public string RowsCounted => Drawing is null ? "rows" : "strokes";

    public required int RowsTotal { get; init; }

    /// <summary>Burn runs completed.</summary>
    public long RunsDone { get; init; }

    /// <summary>Burn runs in the plan.</summary>
    public required long RunsTotal { get; init; }

    /// <summary>How many times the plan was to be burned over the same place (the app's passes); 1 for a single run.</summary>
    public int Passes { get; init; } = 1;

    /// <summary>Passes completed, when <see cref="Passes"/> is above 1; the row and run counts are the last pass's.</summary>
    public int? PassesDone { get; init; }

    /// <summary>
    /// For a laser gate without a watchdog (a frequency-only profile): what then protects the laser when the computer
    /// hangs, as preflight said it and the person accepted it before the run; null (and left out of the file) for a gate with a watchdog.
    /// </summary>
    [System.Text.Json.Serialization.JsonIgnore(Condition = System.Text.Json.Serialization.JsonIgnoreCondition.WhenWritingNull)]
    public string? NoWatchdogAccepted { get; init; }

    /// <summary>The operator's notes, as typed.</summary>
    public string? Notes { get; init; }

    /// <summary>The sample's ID, as typed; also part of the log's file name.</summary>
    public string? SampleId { get; init; }

    /// <summary>The run log this run repeated or resumed (`engrave --from-log`); null for a new job.</summary>
    public string? RepeatOf { get; init; }

    /// <summary>Whether this run resumed <see cref="RepeatOf"/> from its stop point rather than starting over.</summary>
    public bool Resumed { get; init; }

    /// <summary>For a drawing: how it was read, placed and ordered (the image fields then describe the drawing's file); null for an image.</summary>
    public RunDrawing? Drawing { get; init; }

    /// <summary>For a job of layers: each layer in the order it ran (the fields above then describe the first layer's file, and the times and counts the whole run); null otherwise.</summary>
    public IReadOnlyList<RunLayer>? Layers { get; init; }

    /// <summary>The timing doubts the run went on from (a position query too late with the laser off, on a busy computer); null when none.</summary>
    public IReadOnlyList<RunRecovery>? Recoveries { get; init; }

    /// <summary>
    /// What the stage's line dropped during the run (an unfinished frame after a proven gap), one line each with the run's
    /// seconds and the port; at most <see cref="MaxLineWarnings"/>, the rest counted in the last; null when nothing was.
    /// </summary>
    public IReadOnlyList<string>? LineWarnings { get; init; }

    /// <summary>How many <see cref="LineWarnings"/> a record keeps.</summary>
    public const int MaxLineWarnings = 50;

    /// <summary>For a job of layers: its job file and SHA-256 (a resume refuses a changed file); null otherwise.</summary>
    public RunJobFile? JobFile { get; init; }

    /// <summary>On the simulator: what the twin measured of the edges and pulses (null on the machine).</summary>
    public RunSimulation? Simulation { get; init; }

    /// <summary>On real ports: the flight recorder's file beside this log (null on the simulator, or when nothing was recorded).</summary>
    public RunRecording? Recording { get; init; }

    /// <summary>The version of the LaserEngrave.Core assembly, as built (its informational version, with the source revision when known).</summary>
    public static string CurrentSoftwareVersion { get; } = ReadSoftwareVersion();

    /// <summary>
    /// The record of a job about to run: its parameters filled in, started and ended at <paramref name="startedAt"/>,
    /// outcome <see cref="RunOutcome.Failed"/> (what an unfinished record should say) until the caller sets the result.
    /// </summary>
    public static RunRecord ForJob(PreparedJob job, string imageSha256, DateTimeOffset startedAt)
    {
        ArgumentNullException.ThrowIfNull(job);
        ArgumentException.ThrowIfNullOrWhiteSpace(imageSha256);
        return new RunRecord
        {
            SoftwareVersion = CurrentSoftwareVersion,
            StartedAt = startedAt,
            EndedAt = startedAt,
            Outcome = RunOutcome.Failed,
            Image = new RunImage(Path.GetFullPath(job.Spec.ImagePath), imageSha256, job.Mask.Width, job.Mask.Height),
            Mask = job.Spec.Mask,
            Geometry = RunGeometry.From(job.Geometry, job.Spec.Origin),
            Plan = job.Spec.Plan,
            Process = job.Spec.Process,
            Profile = job.Spec.Profile,
            EstimatedSeconds = job.Statistics.WholeRunSeconds(job.Spec.Passes),
            EstimatedEngravingSeconds = job.Statistics.EngravingSeconds * Math.Max(1, job.Spec.Passes),
            RowsTotal = job.Statistics.Rows,
            RunsTotal = job.Statistics.BurnRuns,
        };
    }

    /// <summary>The record of a drawing about to run, as <see cref="ForJob"/> for an image; the image's pixel size is 0 x 0.</summary>
    public static RunRecord ForDrawing(PreparedDrawing drawing, string sha256, DateTimeOffset startedAt)
    {
        ArgumentNullException.ThrowIfNull(drawing);
        ArgumentException.ThrowIfNullOrWhiteSpace(sha256);
        var spec = drawing.Spec;
        var plan = drawing.Plan;
        var schedule = drawing.Schedule;
        return new RunRecord
        {
            SoftwareVersion = CurrentSoftwareVersion,
            StartedAt = startedAt,
            EndedAt = startedAt,
            Outcome = RunOutcome.Failed,
            Image = new RunImage(Path.GetFullPath(spec.ImagePath), sha256, 0, 0),
            Mask = spec.Mask,
            Geometry = new RunGeometry(RunSize.From(spec.Size), 0, 0, plan.MicrostepUm, plan.WidthMm, plan.HeightMm, spec.Origin.X, spec.Origin.Y, 0),
            Plan = spec.Plan,
            Process = spec.Process,
            Profile = spec.Profile,
            EstimatedSeconds = drawing.WholeRunSeconds(spec.Passes),
            EstimatedEngravingSeconds = schedule.EstimatedSeconds * Math.Max(1, spec.Passes),
            RowsTotal = schedule.Strokes.Count,
            RunsTotal = drawing.PathsBurned,
            Drawing = new RunDrawing(
                drawing.Vector.ToleranceUm,
                drawing.Vector.Fill,
                drawing.Vector.FillPitchUm,
                !drawing.Vector.Optimize,
                plan.Scale,
                plan.Paths.Count,
                schedule.Strokes.Count,
                plan.BurnLengthMm,
                plan.TravelMm,
                schedule.PredictedDeviationUm),
        };
    }

    private static string ReadSoftwareVersion()
    {
        var assembly = typeof(RunRecord).Assembly;
        var informational = assembly.GetCustomAttribute<AssemblyInformationalVersionAttribute>()?.InformationalVersion;
        return !string.IsNullOrEmpty(informational) ? informational : assembly.GetName().Version?.ToString() ?? "unknown";
    }
}
