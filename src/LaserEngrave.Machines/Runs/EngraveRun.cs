using System.Globalization;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Marks;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Machines.Runs;

/// <summary>
/// The one run every front end starts (the command line's engrave, the app's Start and Continue, the HTTP API): the checks
/// before anything opens, the session on the machine with the log and the flight recorder, and the sample counter after.
/// </summary>
/// <remarks>
/// In three steps so that a front end can hold the session between them (pause, resume, abort, progress):
/// <see cref="Check"/>, then <see cref="Open"/> on the machine the front end opened, then <see cref="RunAsync"/>. The front
/// ends only render the refusal and the end in their own words (an exit code, the run bar, a 4xx answer).
/// </remarks>
public sealed class EngraveRun
{
    public EngraveRun(RunRequest request, RunLog log)
    {
        ArgumentNullException.ThrowIfNull(request);
        ArgumentNullException.ThrowIfNull(log);
        Request = request;
        Log = log;
    }

    public RunRequest Request { get; }

    public RunLog Log { get; }

    /// <summary>
    /// Why the run must not start, before any port opens and anything moves: a job that cannot run as planned, a log
    /// folder that takes no file, marks a completed run burned already; null when it may start.
    /// </summary>
    public RunRefusal? Check()
    {
        if (Unrunnable(Request.Job) is { } unrunnable)
        {
            return new RunRefusal(RunRefusalReason.Unrunnable, unrunnable);
        }

        try
        {
            // A run must not start without a place for its log (a read-only or full disk is found now, not after the burn).
            Log.CheckWritable();
        }
        catch (RunLogException ex)
        {
            return new RunRefusal(RunRefusalReason.LogNotWritable, ex.Message, ex);
        }

        try
        {
            // Marks whose numbers a completed run burned already are not burned again (two samples, one number); a continue is.
            if (!Request.Continues && Request.JobFile is { } jobFile && MarkManifest.BurnedAlready(jobFile) is { } burned)
            {
                return new RunRefusal(RunRefusalReason.MarksBurnedAlready, burned);
            }
        }
        catch (MarkException ex)
        {
            return new RunRefusal(RunRefusalReason.MarksBurnedAlready, ex.Message, ex);
        }

        return null;
    }

    /// <summary>The session of this run on <paramref name="machine"/>, ready to run; the front end holds it for pause, resume and abort.</summary>
    /// <param name="recorder">The flight recorder of real ports' links (every byte with its time, named in the log); null on the twin.</param>
    public EngraveSession Open(EngraveMachine machine, WireRecorder? recorder)
    {
        ArgumentNullException.ThrowIfNull(machine);
        var request = Request;
        return new EngraveSession(machine, request.Job, new EngraveSessionOptions
        {
            Notes = request.Notes,
            SampleId = request.SampleId,
            RepeatOf = string.IsNullOrEmpty(request.RepeatOf) ? null : request.RepeatOf,
            ResumeFrom = request.ResumeFrom,
            ResumeLayers = request.ResumeLayers,
            JobFile = request.JobFile,
            Home = request.Home,
            AcceptNoWatchdog = request.AcceptNoWatchdog,
            Log = Log.Writer,
            Recorder = recorder,
            WallClock = request.WallClock,
        });
    }

    /// <summary>Runs the session to its end (faults and refusals in the result, never thrown), then advances the sample counter of a completed run of marks.</summary>
    public static async Task<RunEnd> RunAsync(EngraveSession session, IProgress<EngraveProgress>? progress, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(session);
        var result = await session.RunAsync(progress, cancellationToken).ConfigureAwait(false);
        if (session.Options.JobFile is not { } jobFile)
        {
            return new RunEnd(result, null, null);
        }

        try
        {
            // A job of marks advances the sample counter when, and only when, its run completed (docs/marking.md).
            return new RunEnd(result, MarkManifest.AfterRun(jobFile, result.Record.Outcome == RunOutcome.Completed, result.Record.JobFile?.Marks is { } logged ? (logged.Counter, logged.FirstNumber, logged.Count) : null), null);
        }
        catch (Exception ex) when (ex is MarkException or IOException or UnauthorizedAccessException)
        {
            // The run is over and logged; a counter that cannot be written must not hide that.
            return new RunEnd(result, null, ex.Message);
        }
    }

    /// <summary>
    /// Why <paramref name="job"/> cannot run as planned, one line naming the part and its figures: outside the stage's
    /// travel, or nothing to burn (an all-white image, a drawing without a path long enough); null when it can.
    /// </summary>
    /// <remarks>The same rule for a run, its frame and every front end: the job's own start problem, said with its figures.</remarks>
    public static string? Unrunnable(EngraveJob job)
    {
        ArgumentNullException.ThrowIfNull(job);
        if (job.StartProblem is not { } problem)
        {
            return null;
        }

        // A part outside the travel first: a job of layers names only that as its start problem.
        if ((job.Parts.FirstOrDefault(p => !p.FitsTravel) ?? job.Parts.FirstOrDefault(p => p.StartProblem is not null)) is not { } part)
        {
            return problem;
        }

        var spec = part.Spec;
        if (!part.FitsTravel)
        {
            // The job rules' sentence, as the origin field and a drop on the stage say it.
            var (width, height) = part.SizeMm;
            var drawing = part is DrawingPart;
            var which = job.Layers is null ? (drawing ? "drawing" : "job") : $"layer \"{part.Layer.Name}\"";
            return JobRules.OutsideTravel(which, width, height, spec, drawing ? ", with its strokes' run-ups and run-outs" : string.Empty);
        }

        // Nothing to burn: the part's own words, after the file they are about (and its warnings, which say why).
        var warnings = part.Warnings.ToList();
        return $"{spec.ImagePath}: {part.StartProblem}{(warnings.Count == 0 ? string.Empty : $" ({string.Join("; ", warnings)})")}";
    }
}
