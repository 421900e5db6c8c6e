using LaserEngrave.Core.Jobs;

namespace LaserEngrave.Core.Logging;

/// <summary>Turns a logged run back into the job that repeats it, refusing when the image is gone or has changed.</summary>
public static class RunReplay
{
    /// <summary>
    /// The job of <paramref name="record"/>: same image, mask, size, origin, plan, process and profile. Throws
    /// <see cref="RunLogException"/> when the image is not at its logged path or its SHA-256 differs from the logged one.
    /// </summary>
    public static JobSpec ToJobSpec(RunRecord record)
    {
        ArgumentNullException.ThrowIfNull(record);
        var image = record.Image;
        CheckUnchanged(image.Path, image.Sha256, "image");

        return new JobSpec
        {
            ImagePath = image.Path,
            Mask = record.Mask,
            Size = record.Geometry.Size.ToSizeSpec(),
            Origin = new Geometry.OriginMm(record.Geometry.OriginXMm, record.Geometry.OriginYMm),
            Plan = record.Plan,
            Process = record.Process,
            Profile = record.Profile,
            Passes = Math.Clamp(record.Passes, 1, JobSpec.MaxPasses),
        };
    }

    /// <summary>
    /// The layers of a logged run of layers, read again from its job file, and, for <paramref name="resume"/>, where the
    /// run goes on: the first layer not completed, its passes done, and where its pass under way stopped. Throws
    /// <see cref="RunLogException"/> (one line) when the log names no job file, or the job file or any layer's source is
    /// gone or has changed (SHA-256), or nothing is left to resume.
    /// </summary>
    public static (IReadOnlyList<JobLayer> Layers, LayerResumePoint? Resume) ToLayers(RunRecord record, bool resume)
    {
        ArgumentNullException.ThrowIfNull(record);
        var logged = record.Layers ?? throw new RunLogException("the log is not of a job of layers");
        var jobFile = record.JobFile
            ?? throw new RunLogException("the log does not name its job file (written before resumes of layers were logged); run the job file again with --job");
        CheckUnchanged(jobFile.Path, jobFile.Sha256, "job file");
        IReadOnlyList<JobLayer> layers;
        try
        {
            layers = JobFile.Load(jobFile.Path);
        }
        catch (Planning.PlanException ex)
        {
            throw new RunLogException(ex.Message, ex);
        }

        if (layers.Count != logged.Count)
        {
            throw new RunLogException($"{jobFile.Path}: {layers.Count} layers now, {logged.Count} logged; refusing to repeat it");
        }

        for (var i = 0; i < layers.Count; i++)
        {
            if (!string.Equals(Path.GetFullPath(layers[i].Source), logged[i].Source, StringComparison.Ordinal))
            {
                throw new RunLogException($"{jobFile.Path}: layer \"{layers[i].Name}\" burns {layers[i].Source} now, {logged[i].Source} logged; refusing to repeat it");
            }

            CheckUnchanged(logged[i].Source, logged[i].Sha256, $"layer \"{logged[i].Name}\" source");
        }

        if (!resume)
        {
            return (layers, null);
        }

        return (layers, ResumePoint(record));
    }

    /// <summary>
    /// Where a logged run of layers goes on: the first layer not completed, its passes done, and the run's stop point
    /// when that layer had started (the stop point is always the last pass's). Throws <see cref="RunLogException"/> when
    /// every layer completed.
    /// </summary>
    public static LayerResumePoint ResumePoint(RunRecord record)
    {
        ArgumentNullException.ThrowIfNull(record);
        var logged = record.Layers ?? throw new RunLogException("the log is not of a job of layers");
        var next = logged.Select((l, i) => (l, i)).FirstOrDefault(x => x.l.PassesDone < x.l.Passes || x.l.Outcome != RunOutcome.Completed);
        if (next.l is null)
        {
            throw new RunLogException($"every layer of the run completed ({string.Join(", ", logged.Select(l => $"\"{l.Name}\" {l.PassesDone} of {l.Passes} passes"))}), so there is nothing to resume; repeat it without --resume");
        }

        var stop = next.l.Outcome is null ? null : record.StoppedAt;
        return new LayerResumePoint(next.i, Math.Clamp(next.l.PassesDone, 0, next.l.Passes - 1), stop);
    }

    /// <summary>Refuses a file that is gone, unreadable or not the one logged (SHA-256), in one line naming it.</summary>
    private static void CheckUnchanged(string path, string sha256, string what)
    {
        if (!File.Exists(path))
        {
            throw new RunLogException($"{path}: the run's {what} is not there any more (moved or deleted); put it back to repeat the run");
        }

        string hash;
        try
        {
            hash = PreparedJob.HashFile(path);
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            throw new RunLogException($"{path}: cannot read the run's {what}: {ex.Message}", ex);
        }

        if (!string.Equals(hash, sha256, StringComparison.OrdinalIgnoreCase))
        {
            throw new RunLogException(
                $"{path}: the {what} has changed since the run (SHA-256 {Short(hash)}... now, {Short(sha256)}... logged); refusing to repeat it");
        }
    }

    private static string Short(string hash) => hash.Length > 12 ? hash[..12] : hash;
}
