using System.Text.Json;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.App.ViewModels;

/// <summary>
/// A run that stopped before its end: what it ran, the job's values then, where it stopped, and for a job of layers
/// its layers then and where it goes on.
/// </summary>
internal sealed record StoppedRun(EngraveJob Job, JobSettings Settings, RunStopPoint StopPoint, LayerResumePoint? LayerResume, IReadOnlyList<JobLayer>? Layers);

/// <summary>The job as Start would run it now, against which a stopped run is compared.</summary>
/// <param name="Layers">The layers Start runs; null when it runs the single job.</param>
/// <param name="Settings">The single job's values now (asked for only when they are compared).</param>
/// <param name="Mask">The single job's mask now.</param>
internal sealed record JobNow(IReadOnlyList<JobLayer>? Layers, Func<JobSettings> Settings, BitMask? Mask);

/// <summary>
/// The run bar's Continue and the history's: the run that stopped last, and why a stopped run (that one, or a logged one)
/// cannot go on with the job as it is now. Holds no view-model: it is told the job as it is when asked.
/// </summary>
internal sealed class StoppedRuns
{
    // The answer for one plan version of the job and of the layers: comparing the values is not done on every read.
    private ((int Job, int Layers) PlanVersion, string? Reason) _check = ((-1, -1), null);

    /// <summary>The run that stopped last; null when the last run completed or none ran.</summary>
    public StoppedRun? Last { get; private set; }

    /// <summary>A run ended: <paramref name="stopped"/> when it stopped with something left, else null.</summary>
    public void Ended(StoppedRun? stopped)
    {
        Last = stopped;
        _check = ((-1, -1), null);
    }

    /// <summary>
    /// A run of <paramref name="job"/> with <paramref name="settings"/> ended as <paramref name="record"/> says: the run it
    /// leaves to continue (a failed or aborted one with something left), and where it stopped; null when nothing is left.
    /// </summary>
    /// <param name="layers">The layers it ran, for a job of layers.</param>
    public RunStopPoint? Ended(EngraveJob job, JobSettings settings, RunRecord record, IReadOnlyList<JobLayer>? layers)
    {
        var layered = job.Layers is not null;
        var stopPoint = record.Outcome is RunOutcome.Failed or RunOutcome.Aborted ? record.StoppedAt : null;
        var layerResume = layered ? LayerResume(record) : null;
        if (layered && layerResume is null)
        {
            stopPoint = null;
        }

        Ended(stopPoint is null ? null : new StoppedRun(job, settings, stopPoint, layerResume, layered ? layers : null));
        return stopPoint;
    }

    /// <summary>What about the job now differs from the one the last run stopped on, as one line; null when nothing does.</summary>
    public string? Difference((int Job, int Layers) planVersion, JobNow now)
    {
        if (_check.PlanVersion != planVersion)
        {
            _check = (planVersion, Last is { } stopped ? JobDifference(stopped, now) : "no stopped run to continue");
        }

        return _check.Reason;
    }

    /// <summary>
    /// Why the logged run at <paramref name="path"/> cannot be continued from the run history, for what its log says:
    /// one line; null when its record allows it (what holds the machine is the caller's to add).
    /// </summary>
    public static string? WhyNotLogged(string path, RunRecord? record, IEnumerable<RunLogEntry> history, MachineProfile profile)
    {
        if (record is null)
        {
            return "not a run in the history";
        }

        if (record.Outcome == RunOutcome.Completed)
        {
            return "the run completed: nothing is left to burn (Repeat runs it again)";
        }

        if (record.StoppedAt is null)
        {
            return "its log has no stop point (it stopped before its first move): Repeat runs it whole";
        }

        if (record.Layers is not null)
        {
            return "a job of layers continues from the run bar's Continue, or laserengrave engrave --from-log LOG --resume";
        }

        // Continuing it twice would burn twice what the first continue burned.
        if (history.FirstOrDefault(e => e.Record is { Resumed: true } later && later.RepeatOf == path) is { Record: { } continued } by)
        {
            return $"it was continued already ({Path.GetFileName(by.Path)}, {continued.Outcome.ToString().ToLowerInvariant()}){(continued.Outcome == RunOutcome.Completed ? string.Empty : ": continue that run instead")}";
        }

        return record.Profile != profile
            ? $"it ran with the machine profile \"{record.Profile.Name}\", the app plans with \"{profile.Name}\": continue it with laserengrave engrave --from-log LOG --resume"
            : null;
    }

    /// <summary>Where a stopped run of layers goes on, as the command line's <c>--resume</c> finds it in the log; null when nothing is left.</summary>
    public static LayerResumePoint? LayerResume(RunRecord record)
    {
        try
        {
            return RunReplay.ResumePoint(record);
        }
        catch (RunLogException)
        {
            return null;
        }
    }

    private static string? JobDifference(StoppedRun stopped, JobNow now)
    {
        if (stopped.Job.Layers is not null)
        {
            return now.Layers is { } layers && layers.SequenceEqual(stopped.Layers ?? [])
                ? null
                : "the layers changed since the run stopped: continuing would not match what is burned; set them back to continue, or start again";
        }

        if (now.Layers is not null)
        {
            return "Start runs the layers now: clear them to continue the stopped job";
        }

        var current = JsonSerializer.SerializeToElement(now.Settings(), JsonSerializerOptions.Web);
        var then = JsonSerializer.SerializeToElement(stopped.Settings, JsonSerializerOptions.Web);
        var changed = then.EnumerateObject()
            .Where(p => !current.TryGetProperty(p.Name, out var value) || value.GetRawText() != p.Value.GetRawText())
            .Select(p => p.Name)
            .Where(name => name != "passes")
            .Select(JobSettings.FieldLabel)
            .ToList();
        if (changed.Count == 0 && stopped.Job.Mask is { } burned && (now.Mask is not { } mask || !mask.ContentEquals(burned)))
        {
            changed.Add("image");
        }

        return changed.Count == 0 ? null
            : $"the job changed since the run stopped ({string.Join(", ", changed)}): continuing would not match what is burned; set it back to continue, or start again";
    }
}
