using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Logging;

/// <summary>Turns a logged run back into the job that repeats it, refusing when the image is gone or has changed.</summary>
public static class RunReplay
{
    /// <summary>
    /// The job of <paramref name="record"/>: same image, mask, size, origin, plan, process and profile. Throws
    /// <see cref="RunLogException"/> when the image is not at its logged path or its SHA-256 differs from the logged one.
    /// </summary>
    public static JobSpec ToJobSpec(RunRecord record, string source = "run log")
    {
        ArgumentNullException.ThrowIfNull(record);
        Check(record, source);
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
            Passes = record.Passes,
        };
    }

    /// <summary>
    /// The stop point of <paramref name="record"/> as a move of this program's plan of its job. A version 1 log may come
    /// from a program whose planner numbered the moves otherwise (the QR at 5 mm: row 15 began at move 191 then, after
    /// move 191 now), so its move index can name another place of today's plan. Its burn runs are the same, in the same
    /// order, and the log counts those finished (<see cref="RunRecord.RunsDone"/>): such a stop point is taken as the
    /// start of the first burn run not finished, where the program that wrote it would have gone on (a run cut in the
    /// middle burned again from its start, as that program did). Any other stop point is returned as it is.
    /// </summary>
    /// <param name="record">The log of the run to resume.</param>
    /// <param name="plan">The plan of the job the log repeats; asked only for a version 1 image job of one pass.</param>
    public static RunStopPoint? StopPointInPlan(RunRecord record, Func<Planning.RasterPlan> plan)
    {
        ArgumentNullException.ThrowIfNull(record);
        ArgumentNullException.ThrowIfNull(plan);
        if (record.StoppedAt is not { } stop || record.ReadFromSchemaVersion > 1 || record.Passes > 1 || record.Layers is not null
            || record.Drawing is not null || record.Process.Mode != Planning.PlanMode.Raster)
        {
            return record.StoppedAt;
        }

        long index = 0;
        long burns = 0;
        long? nextRun = null;
        var nextRunRow = 0;
        var agrees = false;
        foreach (var move in plan().Moves())
        {
            if (index == stop.MoveIndex)
            {
                agrees = burns == record.RunsDone && move.Row == stop.Row;
            }

            if (move.Kind == Planning.MoveKind.Burn)
            {
                if (burns == record.RunsDone && nextRun is null)
                {
                    nextRun = index;
                    nextRunRow = move.Row;
                }

                burns++;
            }

            index++;
        }

        return agrees || nextRun is not { } start ? stop : stop with { MoveIndex = start, Row = nextRunRow, ResumeXMicrosteps = null, CutPixel = null, ExpectedXMicrosteps = null };
    }

    /// <summary>
    /// Throws <see cref="RunLogException"/> "SOURCE: FIELD ..." for the first logged value a repeat or resume could not
    /// use: a log is a file anyone can edit, so its values meet the command line's rules before anything moves.
    /// </summary>
    public static void Check(RunRecord record, string source)
    {
        ArgumentNullException.ThrowIfNull(record);
        if (Problem(record) is { } problem)
        {
            throw new RunLogException($"{source}: {problem}");
        }
    }

    /// <summary>Null when every value a repeat or resume reads from <paramref name="record"/> is usable; otherwise the field and the rule.</summary>
    public static string? Problem(RunRecord record)
    {
        ArgumentNullException.ThrowIfNull(record);

        // Sections given as null in the JSON arrive here as null despite their types.
        var sections = new (string Name, object? Value)[]
        {
            ("image", record.Image), ("mask", record.Mask), ("geometry", record.Geometry), ("plan", record.Plan), ("process", record.Process), ("profile", record.Profile),
        };
        if (sections.FirstOrDefault(s => s.Value is null) is { Name: { } missing })
        {
            return $"{missing} is missing (null): not a log a run can be repeated from";
        }

        if (string.IsNullOrWhiteSpace(record.Image.Path))
        {
            return "image.path is empty";
        }

        if (MachineProfileValidator.Problems(record.Profile) is [var first, ..])
        {
            return $"profile.{first}";
        }

        var plan = record.Plan;
        if (!Enum.IsDefined(plan.Strategy))
        {
            return $"plan.strategy {plan.Strategy} is not known (paper or optimized)";
        }

        if (!Enum.IsDefined(record.Mask.Dither))
        {
            return $"mask.dither {record.Mask.Dither} is not one of the known";
        }

        if (record.Mask.QuarterTurns is < 0 or > 3)
        {
            return $"mask.quarterTurns {record.Mask.QuarterTurns} is not 0, 1, 2 or 3";
        }

        if (record.Geometry.Size is not { } size)
        {
            return "geometry.size is missing (null)";
        }

        SizeSpec asked;
        try
        {
            asked = size.ToSizeSpec();
        }
        catch (RunLogException ex)
        {
            return $"geometry.size: {ex.Message}";
        }

        // The job's own rules, as the command line and the app apply them; only the names are the log's.
        var settings = JobSettings.From(new JobSpec
        {
            ImagePath = record.Image.Path,
            Mask = record.Mask,
            Size = asked,
            Origin = new OriginMm(record.Geometry.OriginXMm, record.Geometry.OriginYMm),
            Plan = plan,
            Process = record.Process,
            Passes = record.Passes,
        });
        // The dot values are checked in raster mode too: the repeated job carries them as logged.
        if (JobRules.Check(settings with { Mode = Planning.PlanMode.Dots }, MachineLimits.Of(record.Profile)) is [var problem, ..])
        {
            return problem.Field == JobField.Pitch && size.PitchUm is null && size.Dpi is { } resolution
                ? $"geometry.size.dpi {N(resolution)} gives pixels of {problem.ValueText} µm: {problem.Rule}"
                : problem.MessageFor(LogField(problem.Field));
        }

        // What only a process carries (the baud rates, a mode by number), by the same rules, before it is used.
        if (JobRules.Check(record.Process, MachineLimits.Of(record.Profile)) is [var processProblem, ..])
        {
            return processProblem.MessageFor(LogField(processProblem.Field));
        }

        return record.StoppedAt is { } stop ? StopProblem(stop, record.Profile) : null;
    }

    /// <summary>Where a job field stands in a run log.</summary>
    private static string LogField(string field) => field switch
    {
        JobField.Threshold => "mask.thresholdPercent",
        JobField.Width or JobField.Height or JobField.Pitch => $"geometry.size.{field}",
        JobField.OriginX or JobField.OriginY => $"geometry.{field}",
        JobField.Overscan => "plan.overscanMm",
        JobField.Passes => "passes",
        _ => $"process.{field}",
    };

    private static string? StopProblem(RunStopPoint stop, Geometry.MachineProfile profile)
    {
        if (stop.Row < 0 || stop.MoveIndex < 0)
        {
            return stop.Row < 0 ? $"stoppedAt.row {stop.Row} must not be negative" : $"stoppedAt.moveIndex {stop.MoveIndex} must not be negative";
        }

        var positions = new (string Field, long? Value, long Travel)[]
        {
            ("xMicrosteps", stop.XMicrosteps, profile.X.TravelMicrosteps), ("yMicrosteps", stop.YMicrosteps, profile.Y.TravelMicrosteps),
            ("resumeXMicrosteps", stop.ResumeXMicrosteps, profile.X.TravelMicrosteps), ("expectedXMicrosteps", stop.ExpectedXMicrosteps, profile.X.TravelMicrosteps),
        };
        if (positions.FirstOrDefault(p => p.Value is { } v && (v < 0 || v > p.Travel)) is { Field: { } field } bad)
        {
            return $"stoppedAt.{field} {bad.Value} must be within the travel 0..{bad.Travel} microsteps";
        }

        return stop.CutPixel is { } pixel && (pixel.Column < 0 || pixel.Row < 0)
            ? $"stoppedAt.cutPixel {pixel.Column}, {pixel.Row} must not be negative"
            : null;
    }

    private static string N(double value) => MachineLimits.Text.N(value);

    /// <summary>
    /// The layers of a logged run of layers, read again from its job file, and, for <paramref name="resume"/>, where the
    /// run goes on: the first layer not completed, its passes done, and where its pass under way stopped. Throws
    /// <see cref="RunLogException"/> (one line) when the log names no job file, or the job file or any layer's source is
    /// gone or has changed (SHA-256), or nothing is left to resume.
    /// </summary>
    /// <param name="record">The log.</param>
    /// <param name="resume">Also where the run goes on.</param>
    /// <param name="source">How messages name the log.</param>
    /// <param name="burning">The layers are to be burned (a repeat, a resume): marks whose numbers a completed run burned are refused. A replay burns nothing.</param>
    public static (IReadOnlyList<JobLayer> Layers, LayerResumePoint? Resume) ToLayers(RunRecord record, bool resume, string source = "run log", bool burning = true)
    {
        ArgumentNullException.ThrowIfNull(record);
        if (record.StoppedAt is { } stopped && StopProblem(stopped, record.Profile ?? MachineProfile.Default) is { } problem)
        {
            throw new RunLogException($"{source}: {problem}");
        }

        var logged = record.Layers ?? throw new RunLogException("the log is not of a job of layers");
        var jobFile = record.JobFile
            ?? throw new RunLogException("the log does not name its job file (written before resumes of layers were logged); run the job file again with --job");
        CheckUnchanged(jobFile.Path, jobFile.Sha256, "job file");
        // A repeat of a completed run, or a second continue of a stopped one, would burn numbers a completed run burned.
        if (burning && jobFile.Marks is { Count: > 0 } burned && new Marks.MarkCounter(burned.Counter).Burned(burned.FirstNumber, burned.Count))
        {
            throw new RunLogException($"{jobFile.Path}: a completed run burned its marks' numbers {burned.FirstNumber}..{burned.FirstNumber + burned.Count - 1}; run the job file again with --job for the next numbers (or laserengrave mark for a new folder), so no two samples carry one number");
        }

        IReadOnlyList<JobLayer> layers;
        try
        {
            // The job file's marks made again as the run made them: from its first number and its time, so the files are the ones logged.
            var marks = jobFile.Marks is { MadeAt: { } madeAt } made
                ? new Marks.JobMarks(made.Counter, record.Profile ?? MachineProfile.Default, madeAt, record.SampleId) { FirstNumber = made.FirstNumber }
                : null;
            layers = JobFile.Load(jobFile.Path, marks);
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
