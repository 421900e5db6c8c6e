using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Sweeps;
using LaserEngrave.Devices.Scheduling;
using LaserEngrave.Wire.Scheduling;

namespace LaserEngrave.Devices.Execution;

/// <summary>
/// One engraving, as the command line and the app both run it: the log's record, every pass (one
/// <see cref="RunExecutor"/> each), the simulator's burn check, and the log written, with progress as it goes.
/// </summary>
/// <remarks>
/// The front ends only render it: they mirror <see cref="State"/> and <see cref="EngraveProgress"/>, and call
/// <see cref="Pause"/>, <see cref="Resume"/> and <see cref="Abort"/> (from any thread, at any time). A session runs once.
/// </remarks>
public sealed class EngraveSession
{
    private readonly Lock _lock = new();
    private readonly IReadOnlyList<JobPart> _parts;
    private readonly bool _layered;
    private long _moves;
    private int _layer = 1;

    // The pass under way within its layer and that layer's passes (the progress's "pass 2 of 3"; a job of layers is not
    // one job of their summed passes).
    private int _layerPass = 1;
    private int _layerPasses = 1;
    private readonly int _firstLayer;
    private readonly RunStopPoint? _resumeFrom;
    private RunExecutor? _current;
    private EngraveProgress _progress;
    private IProgress<EngraveProgress>? _sink;

    // The run's phase and its pause and abort as asked, held once for every pass (each pass's executor acts on the same one and
    // moves its phase); the session reads it.
    private readonly RunControl _control = new();
    private readonly List<RunRecovery> _recoveries = [];
    private bool _recovering;
    private double _latencyScale = 1;
    private int _started;

    /// <summary>
    /// How many timing doubts (<see cref="RunResult.Recoverable"/>) a session goes on from at one place of the job, each no
    /// further than the one before; the next one ends the run. A doubt further on (a busy computer late to switch the laser
    /// on now and then, docs/execution.md, "Late switchings") counts afresh, up to <see cref="MaxRecoveriesInAll"/>.
    /// </summary>
    public const int MaxRecoveries = 3;

    /// <summary>
    /// How many timing doubts a session goes on from in one pass (of one layer): a bound on a pass that would otherwise
    /// go on for ever, counted per pass so that a job of many passes on a busy computer is not cut short by its length.
    /// </summary>
    public const int MaxRecoveriesInAll = 100;

    /// <summary>A session that engraves <paramref name="job"/>: an image (raster or dots), a drawing, or a job of layers one layer after the other, each with its own process and passes, all in one log.</summary>
    /// <remarks>A stopped run of layers is continued with <see cref="EngraveSessionOptions.ResumeLayers"/>, not <see cref="EngraveSessionOptions.ResumeFrom"/>. A sweep runs cell by cell through <see cref="SweepSession"/>, each cell a session of its own.</remarks>
    public EngraveSession(EngraveMachine machine, EngraveJob job, EngraveSessionOptions? options = null)
    {
        ArgumentNullException.ThrowIfNull(machine);
        ArgumentNullException.ThrowIfNull(job);
        if (job is SweepJob)
        {
            throw new ArgumentException("a sweep runs cell by cell through SweepSession, each cell its own session and log", nameof(job));
        }

        var parts = job.Parts;
        var layered = job is LayersJob;
        Engraving = job;
        Job = (parts[0] as ImagePart)?.Image;
        Drawing = (parts[0] as DrawingPart)?.Drawing;
        Machine = machine;
        Spec = job.Spec;
        Options = options ?? EngraveSessionOptions.Default;
        _parts = parts;
        _layered = layered;
        foreach (var part in parts)
        {
            ArgumentOutOfRangeException.ThrowIfLessThan(part.Layer.Passes, 1);
            ArgumentOutOfRangeException.ThrowIfGreaterThan(part.Layer.Passes, JobSpec.MaxPasses);
        }

        if (layered && Options.ResumeFrom is not null)
        {
            throw new ArgumentException("a job of layers is continued from its layer's stop point (ResumeLayers), not ResumeFrom", nameof(options));
        }

        if (Options.ResumeLayers is { } resume)
        {
            if (!layered)
            {
                throw new ArgumentException("ResumeLayers is for a job of layers", nameof(options));
            }

            ArgumentOutOfRangeException.ThrowIfNegative(resume.Layer);
            ArgumentOutOfRangeException.ThrowIfGreaterThanOrEqual(resume.Layer, parts.Count);
            ArgumentOutOfRangeException.ThrowIfNegative(resume.PassesDone);
            ArgumentOutOfRangeException.ThrowIfGreaterThanOrEqual(resume.PassesDone, parts[resume.Layer].Layer.Passes);
        }

        _firstLayer = Options.ResumeLayers?.Layer ?? 0;
        _resumeFrom = Options.ResumeFrom ?? Options.ResumeLayers?.StopPoint;

        // Continuing a stopped run finishes the pass that stopped, and only that; a run of layers goes on to its end.
        Passes = Options.ResumeLayers is { } from ? parts.Skip(from.Layer).Sum(p => p.Layer.Passes) - from.PassesDone
            : Options.ResumeFrom is null ? parts.Sum(p => p.Layer.Passes)
            : 1;
        _moves = parts[_firstLayer].Moves;
        _layer = _firstLayer + 1;
        var first = parts[_firstLayer];
        (_layerPass, _layerPasses) = ((Options.ResumeLayers?.PassesDone ?? 0) + 1, Options.ResumeFrom is null ? first.Layer.Passes : 1);
        _progress = new EngraveProgress(RunState.Idle, 1, Passes, 0, _moves, false, RunExecutor.IdleProgress(first), LayerPass: _layerPass, LayerPasses: _layerPasses);
    }

    public EngraveMachine Machine { get; }

    /// <summary>The job this session engraves.</summary>
    public EngraveJob Engraving { get; }

    /// <summary>The image job (a layered job's first layer's); null for a drawing.</summary>
    public PreparedJob? Job { get; }

    /// <summary>The drawing (a layered job's first layer's); null for an image job.</summary>
    public PreparedDrawing? Drawing { get; }

    /// <summary>The job's spec (the image's or the drawing's).</summary>
    public JobSpec Spec { get; }

    public EngraveSessionOptions Options { get; }

    /// <summary>The passes this session runs: the job's (every layer's added up), or 1 when it continues a stopped run.</summary>
    public int Passes { get; }

    /// <summary>The run's state over all its passes, as its <see cref="RunControl"/> holds it.</summary>
    public RunState State => _control.Phase;

    /// <summary>The latest snapshot.</summary>
    public EngraveProgress Progress
    {
        get
        {
            lock (_lock)
            {
                return _progress;
            }
        }
    }

    /// <summary>Where the pass under way puts the stage at <paramref name="timestamp"/> (of the machine's clock) by its own timing, during a timed stroke; null otherwise (<see cref="RunExecutor.StrokePositionAt"/>).</summary>
    public StrokePosition? StrokePositionAt(long timestamp)
    {
        RunExecutor? current;
        lock (_lock)
        {
            current = _current;
        }

        return current?.StrokePositionAt(timestamp);
    }

    /// <summary>Runs every pass on the machine's own runner (the simulation's loop in virtual time), then checks the burn and writes the log.</summary>
    /// <param name="progress">Told of every state change and move, on the run's thread, synchronously: keep it quick.</param>
    /// <param name="cancellationToken">Cancelling it aborts the run, as <see cref="Abort"/>.</param>
    /// <returns>The record and how the run ended; faults, refusals and a log that cannot be written are in it, never thrown.</returns>
    public Task<EngraveResult> RunAsync(IProgress<EngraveProgress>? progress, CancellationToken cancellationToken)
    {
        if (Interlocked.Exchange(ref _started, 1) != 0)
        {
            throw new InvalidOperationException("an EngraveSession runs once; make a new one");
        }

        _sink = progress;
        return TaskRunner.For(Machine.TimeProvider).Run(() => RunPassesAsync(cancellationToken));
    }

    /// <summary>Holds the run after the current move with the laser off; a pass still to start starts paused.</summary>
    public void Pause()
    {
        RunExecutor? current;
        lock (_lock)
        {
            if (_control.AbortRequested || RunStateMachine.IsEnd(_control.Phase) || _control.PauseRequested)
            {
                return;
            }

            // Asked here as well as of the pass: a pass that has just ended leaves it for the next one.
            _control.RequestPause();
            current = _current;
        }

        current?.Pause();
        Report(null);
    }

    /// <summary>Continues a paused (or pausing) run.</summary>
    public void Resume()
    {
        RunExecutor? current;
        TaskCompletionSource? resumed = null;
        lock (_lock)
        {
            if (!_control.PauseRequested)
            {
                return;
            }

            current = _current;
            if (current is null)
            {
                resumed = _control.RequestResume();
            }
        }

        // The pass withdraws the pause itself, so that it can leave Pausing before its wait is released.
        current?.Resume();
        resumed?.TrySetResult();
        Report(null);
    }

    /// <summary>Laser off, then the stage stopped; no further pass starts.</summary>
    public void Abort()
    {
        RunExecutor? current;
        lock (_lock)
        {
            if (_control.AbortRequested || RunStateMachine.IsEnd(_control.Phase))
            {
                return;
            }

            // Recorded at once, so that no further pass starts, and Aborting at once; the pass that runs carries it out (laser off first).
            _control.RequestAbort();
            current = _current;
        }

        current?.Abort();
        Report(null);
    }

    // The numbers the job's marks burn, as the file's reading made them, so the log carries them for the counter and a resume.
    private static RunJobMarks? MarksOf(string jobFile)
    {
        try
        {
            return RunJobMarks.Beside(jobFile);
        }
        catch (Exception ex) when (ex is Core.Marks.MarkException or IOException or UnauthorizedAccessException)
        {
            // An unreadable record stops no run; the counter is then left as it is and the run's end says so.
            return null;
        }
    }

    private static string HashOrMissing(string path)
    {
        try
        {
            return PreparedJob.HashFile(path);
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            return "unreadable: " + ex.Message;
        }
    }

    private RunRecord NewRecord(JobPart part, DateTimeOffset started)
    {
        var hash = Options.ImageSha256 ?? HashOrMissing(part.Spec.ImagePath);
        // The log names the kind (an image's pixels and mask, a drawing's paths): Core/Logging makes one of each.
        var record = part switch
        {
            DrawingPart { Drawing: var drawing } => RunRecord.ForDrawing(drawing, hash, started),
            ImagePart { Image: var image } => RunRecord.ForJob(image, hash, started),
            _ => throw new ArgumentException($"no log record for a {part.GetType().Name}", nameof(part)),
        };

        // A gate without a watchdog runs only once accepted: the log keeps what the person accepted.
        return !part.Spec.Profile.Gate.HasWatchdog && Options.AcceptNoWatchdog ? record with { NoWatchdogAccepted = LaserGateProfile.NoWatchdogSentence } : record;
    }

    private static RunLayer LayerEntry(JobPart part, double estimatedSeconds)
    {
        var spec = part.Spec;
        var (width, height) = part.SizeMm;
        return new RunLayer(
            part.Layer.Name,
            Path.GetFullPath(spec.ImagePath),
            HashOrMissing(spec.ImagePath),
            part.Layer.Mode,
            part.Layer.DrawingLayer,
            width,
            height,
            spec.Origin.X,
            spec.Origin.Y,
            spec.Process.BurnSpeedMmPerS,
            spec.Process.LaserFrequencyHz,
            part.Layer.Passes)
        {
            EstimatedSeconds = estimatedSeconds,
            EstimatedEngravingSeconds = part.EngravingSeconds * part.Layer.Passes,
        };
    }

    private async Task<EngraveResult> RunPassesAsync(CancellationToken cancellationToken)
    {
        var time = Machine.TimeProvider;
        using var lineWarnings = new LineWarnings(Machine.Stage, time);
        var (record, layers) = StartRecord();

        // On real ports the host's timing is the laser's: the run asks for a higher CPU priority, and the log says what it got.
        using var priority = Machine.Simulated ? null : RunPriority.Raise();
        record = record with { HostPriority = priority?.Description };
        var clockStart = time.GetTimestamp();
        Machine.Inspector?.Begin();
        var tally = new PassTally();
        Exception? error = null;
        try
        {
            for (var index = 0; index < _parts.Count; index++)
            {
                if (!await RunLayerAsync(index, layers, tally, cancellationToken))
                {
                    break;
                }
            }
        }
        catch (Exception ex) when (ex is not OutOfMemoryException)
        {
            // Whatever stopped the run (a preflight refusal, a lost port), the log is still written; the caller reports it.
            error = ex;
        }

        record = FinishRecord(record, layers, tally, error, time.GetElapsedTime(clockStart), lineWarnings.Lines);
        var (files, logError) = WriteLog(record);
        lock (_lock)
        {
            _current = null;
            _control.End(RunStateMachine.EndState(record.Outcome));
        }

        Report(null);
        return new EngraveResult(record, tally.Run, error, files, logError);
    }

    /// <summary>What a session has run so far: the results added up over the passes, the passes done and the pass under way.</summary>
    private sealed class PassTally
    {
        public RunResult? Run { get; set; }

        public int PassesDone { get; set; }

        public int Pass { get; set; }
    }

    /// <summary>The log's record before the run, and a job of layers' entries with each layer's estimate.</summary>
    private (RunRecord Record, List<RunLayer>? Layers) StartRecord()
    {
        var record = NewRecord(_parts[0], Options.WallClock.GetLocalNow()) with
        {
            Simulated = Machine.Simulated,
            Notes = Options.Notes,
            SampleId = Options.SampleId,
            RepeatOf = Options.RepeatOf,
            Resumed = _resumeFrom is not null || Options.ResumeLayers is not null,
            JobFile = Options.JobFile is { } jobFile ? new RunJobFile(Path.GetFullPath(jobFile), HashOrMissing(jobFile)) { Marks = MarksOf(jobFile) } : null,
            Passes = Passes,
        };

        // Each layer's estimate as the job runs it: the first homes, every later one starts where the one before ended.
        var layers = _layered ? _parts.Zip(JobPart.RunSeconds(_parts), LayerEntry).ToList() : null;
        if (layers is not null)
        {
            record = record with { EstimatedSeconds = layers.Sum(l => l.EstimatedSeconds), EstimatedEngravingSeconds = layers.Sum(l => l.EstimatedEngravingSeconds) };
        }

        return (record, layers);
    }

    /// <summary>Runs the passes of the part at <paramref name="index"/>; returns whether the run goes on to the next.</summary>
    private async Task<bool> RunLayerAsync(int index, List<RunLayer>? layers, PassTally tally, CancellationToken cancellationToken)
    {
        var part = _parts[index];
        if (index < _firstLayer)
        {
            // Completed by the run this one continues: logged as it was, not burned again.
            layers![index] = layers[index] with { PassesDone = part.Layer.Passes, Outcome = RunOutcome.Completed, CompletedBefore = true };
            return true;
        }

        var layerPasses = index == _firstLayer ? Options.ResumeLayers?.PassesDone ?? 0 : 0;
        var passes = Options.ResumeFrom is null ? part.Layer.Passes : 1;
        lock (_lock)
        {
            _moves = part.Moves;
            _layer = index + 1;
            (_layerPass, _layerPasses) = (layerPasses + 1, passes);
        }

        if (_layered)
        {
            // The flight recorder notes where each layer begins, so a replay checks each layer's burn alone.
            Options.Recorder?.MarkLayer(index);
        }

        if (index > _firstLayer)
        {
            // Each layer's burn is checked on its own.
            Machine.Inspector?.Begin();
        }

        RunResult? layerRun = null;
        try
        {
            for (var p = layerPasses + 1; p <= passes; p++)
            {
                lock (_lock)
                {
                    _layerPass = p;
                }

                var pass = ++tally.Pass;
                var result = await RecoverAsync(part, pass, await RunPassAsync(part, pass, firstOfSession: pass == 1, cancellationToken), cancellationToken);

                // The log speaks for the whole job: times and laser-on add up over the passes, the counts are the last pass's.
                tally.Run = Add(tally.Run, result);
                layerRun = Add(layerRun, result);
                if (result.Outcome != RunOutcome.Completed)
                {
                    break;
                }

                tally.PassesDone++;
                layerPasses++;
            }
        }
        finally
        {
            if (layers is not null)
            {
                layers[index] = layers[index] with
                {
                    PassesDone = layerPasses,
                    Outcome = layerRun?.Outcome,
                    EngravingSeconds = layerRun?.EngravingDuration.TotalSeconds ?? 0,
                    LaserOnSeconds = layerRun?.LaserOnSeconds ?? 0,
                    Simulation = Machine.Inspector is { } layerInspector && layerRun is not null ? Inspect(layerInspector, part, index == _firstLayer ? _resumeFrom : null) : null,
                };
            }
        }

        return layerRun?.Outcome == RunOutcome.Completed;
    }

    /// <summary>The log's record after the run: its outcome, the twin's inspection, the layers, recoveries and recording.</summary>
    private RunRecord FinishRecord(RunRecord record, List<RunLayer>? layers, PassTally tally, Exception? error, TimeSpan elapsed, IReadOnlyList<string>? lineWarnings)
    {
        if (Machine.Inspector is { } inspector && !_layered)
        {
            record = record with { Simulation = Inspect(inspector, _parts[0], _resumeFrom) };
        }

        record = RunRecords.Complete(record, tally.Run, error, Machine.StagePort, Machine.LaserPort, Options.WallClock.GetLocalNow(), elapsed) with
        {
            PassesDone = Passes > 1 ? tally.PassesDone : null,
            Layers = layers,
            Recoveries = _recoveries.Count > 0 ? [.. _recoveries] : null,
            LineWarnings = lineWarnings,
        };
        if (record.Outcome == RunOutcome.Completed && BurnMismatch(record) is { } mismatch)
        {
            // "Completed" promises the whole image engraved: on the twin, where the burn is known, only when it equals the mask.
            record = record with { Outcome = RunOutcome.Failed, Fault = new RunFault(mismatch, "burn") };
        }

        if (layers is not null)
        {
            // The estimate is the whole job's, whatever part of it ran.
            record = record with { EstimatedSeconds = layers.Sum(l => l.EstimatedSeconds), EstimatedEngravingSeconds = layers.Sum(l => l.EstimatedEngravingSeconds) };
        }

        if (Options.Recorder is { } recorder)
        {
            var recording = recorder.Finish();
            record = record with { Recording = new RunRecording(recording.File, recording.Events, recording.Truncated) };
        }

        return record;
    }

    /// <summary>Writes the log when the session keeps one; a log that could not be written is returned, not thrown.</summary>
    private (RunLogFiles? Files, Exception? Error) WriteLog(RunRecord record)
    {
        if (Options.Log is not { } log)
        {
            return (null, null);
        }

        try
        {
            return (log.Write(record), null);
        }
        catch (Exception ex) when (ex is RunLogException or IOException or UnauthorizedAccessException)
        {
            return (null, ex);
        }
    }

    private static RunResult Add(RunResult? sum, RunResult result) => sum is null ? result : result with
    {
        StartedAt = sum.StartedAt,
        EngravingDuration = sum.EngravingDuration + result.EngravingDuration,
        EstimatedSeconds = sum.EstimatedSeconds + result.EstimatedSeconds,
        EstimatedEngravingSeconds = sum.EstimatedEngravingSeconds + result.EstimatedEngravingSeconds,
        LaserOnSeconds = sum.LaserOnSeconds + result.LaserOnSeconds,
        LateSwitches = LateSwitches.Add(sum.LateSwitches, result.LateSwitches),
        GuardScale = Math.Max(sum.GuardScale, result.GuardScale),
    };

    /// <summary>
    /// A pass that failed on a timing doubt (<see cref="RunResult.Recoverable"/>: a position query too late with the
    /// laser off, nothing burned wrongly, a busy computer) goes on from its stop point, as a resume would, through the
    /// resumed run's own checks; at most <see cref="MaxRecoveries"/> times at one place, never after an abort. Anything
    /// else ends the run.
    /// </summary>
    private async Task<RunResult> RecoverAsync(JobPart part, int pass, RunResult result, CancellationToken cancellationToken)
    {
        var atOnePlace = 0;
        var inThisPass = 0;
        long? lastStop = null;
        while (result is { Outcome: RunOutcome.Failed, Recoverable: true, StopPoint: { } stop } && inThisPass++ < MaxRecoveriesInAll
            && (atOnePlace = lastStop is { } last && stop.MoveIndex <= last ? atOnePlace + 1 : 1) <= MaxRecoveries
            && !cancellationToken.IsCancellationRequested && !AbortRequested())
        {
            lastStop = stop.MoveIndex;
            lock (_lock)
            {
                _recoveries.Add(new RunRecovery(pass, result.FaultMessage ?? "a timing doubt", stop.MoveIndex, stop.Row));
                _recovering = true;
            }

            EngraveProgress stopped;
            lock (_lock)
            {
                stopped = _progress;
            }

            RunResult again;
            try
            {
                again = await RunPassAsync(part, pass, firstOfSession: false, cancellationToken, resumeFrom: stop);
            }
            catch (Exception ex) when (ex is not OperationCanceledException and not OutOfMemoryException)
            {
                // Going on needs the machine to pass its checks again (a stage gone silent does not): the run ends on the
                // first fault, with its stop point, so that a resume later starts there. What the machine did comes first
                // (which device, what it did); the doubt that led to it after. The progress is the stopped pass's again, not
                // the new pass's start (row 0, the stage at 0, 0), so the run bar and the cross agree with the log.
                lock (_lock)
                {
                    _progress = stopped with { Recovering = false };
                    _recovering = false;
                }

                return result with { FaultMessage = $"{ex.Message.ReplaceLineEndings(" ")}, while going on after a timing doubt ({result.FaultMessage})" };
            }

            result = again with
            {
                StartedAt = result.StartedAt,
                EngravingDuration = result.EngravingDuration + again.EngravingDuration,
                EstimatedSeconds = result.EstimatedSeconds,
                EstimatedEngravingSeconds = result.EstimatedEngravingSeconds,
                LaserOnSeconds = result.LaserOnSeconds + again.LaserOnSeconds,
                LateSwitches = LateSwitches.Add(result.LateSwitches, again.LateSwitches),
                GuardScale = Math.Max(result.GuardScale, again.GuardScale),
            };
        }

        // An abort (a signal, the Abort button) asked as a pass ended on a doubt it would have gone on from is what ended
        // the run: it ends aborted, with the doubt's stop point, not as a failure on the doubt.
        if (result is { Outcome: RunOutcome.Failed, Recoverable: true } && (cancellationToken.IsCancellationRequested || AbortRequested()))
        {
            return result with { Outcome = RunOutcome.Aborted, FaultMessage = RunExecutor.AbortedMessage, Recoverable = false };
        }

        return result;
    }

    private bool AbortRequested()
    {
        return _control.AbortRequested;
    }

    /// <summary>
    /// Null when the twin's burn of every image equals its mask (or nothing measured it: a real machine, a drawing); otherwise
    /// the one line that says how it differs.
    /// </summary>
    internal static string? BurnMismatch(RunRecord record)
    {
        var measured = record.Layers is { } layers
            ? layers.Select((l, i) => (Name: $"layer {i + 1}: ", l.Simulation, Image: l.Simulation?.Path is null))
            : [(Name: string.Empty, record.Simulation, Image: record.Drawing is null)];
        foreach (var (name, simulation, image) in measured)
        {
            if (image && simulation is { } sim && (sim.MissingPixels > 0 || sim.ExtraPixels > 0))
            {
                return string.Create(CultureInfo.InvariantCulture, $"{name}the burn does not equal the mask: {sim.MissingPixels} black pixels got no pulse and {sim.ExtraPixels} white pixels got one (the simulator's count), so the image was not engraved whole");
            }
        }

        return null;
    }

    // A continued run is checked against what it had still to burn, not what the run it continues burned. The twin
    // checks an image against its mask and a drawing against its paths: two inspections (IRunInspector), one per kind.
    private static RunSimulation Inspect(IRunInspector inspector, JobPart part, RunStopPoint? resumedFrom) =>
        part switch
        {
            DrawingPart { Drawing: var drawing } => inspector.InspectDrawing(drawing),
            ImagePart { Image: var image } => inspector.Inspect(image, resumedFrom),
            _ => throw new ArgumentException($"no inspection of a {part.GetType().Name}", nameof(part)),
        };

    private async Task<RunResult> RunPassAsync(JobPart part, int pass, bool firstOfSession, CancellationToken cancellationToken, RunStopPoint? resumeFrom = null)
    {
        // What an earlier run of this session found of the latencies' spread holds for the rest of it (RunResult.LatencyScale).
        var options = new RunOptions { Home = Options.Home && firstOfSession, ResumeFrom = resumeFrom ?? (firstOfSession ? _resumeFrom : null), LatencyScale = _latencyScale, AcceptNoWatchdog = Options.AcceptNoWatchdog };
        var executor = new RunExecutor(Machine.Stage, Machine.Gate, part, Machine.TimeProvider, options, _control);
        var movesDone = options.ResumeFrom?.MoveIndex ?? 0;
        executor.MoveCompleted += (_, e) => Interlocked.Exchange(ref movesDone, e.MoveIndex + 1);
        executor.ProgressChanged += (_, p) => Report(new PassProgress(pass, Interlocked.Read(ref movesDone), p));
        bool pause;
        bool abort;
        lock (_lock)
        {
            _current = executor;
            pause = _control.PauseRequested;
            abort = _control.AbortRequested;
        }

        // A pause or an abort asked between passes holds or stops this one before it moves.
        if (pause)
        {
            executor.Pause();
        }

        if (abort)
        {
            executor.Abort();
        }

        var result = await executor.RunAsync(cancellationToken);
        _latencyScale = Math.Max(_latencyScale, result.LatencyScale);
        return result;
    }

    private void Report(PassProgress? pass)
    {
        EngraveProgress progress;
        lock (_lock)
        {
            var state = _control.Phase;
            if (RunStateMachine.IsEnd(state) && pass is not null)
            {
                // A pass's report that comes after the session's end (an abort's, from another thread) changes nothing.
                return;
            }

            // A recovery lasts until the pass it goes on with has left its preflight.
            _recovering &= state == RunState.Preflight;

            // The state is the run's phase, which a pass's end does not end (RunControl.Entered).
            _progress = pass is { } p
                ? new EngraveProgress(state, p.Pass, Passes, p.MovesDone, _moves, _control.PauseRequested, p.Run, _layer, _recoveries.Count, _recovering, _layerPass, _layerPasses)
                : _progress with { State = state, PauseRequested = _control.PauseRequested, Recoveries = _recoveries.Count, Recovering = _recovering };

            progress = _progress;
        }

        _sink?.Report(progress);
    }

    private readonly record struct PassProgress(int Pass, long MovesDone, RunProgress Run);
}
