using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Scheduling;

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
    private readonly long _moves;
    private RunExecutor? _current;
    private RunState _state = RunState.Idle;
    private EngraveProgress _progress;
    private IProgress<EngraveProgress>? _sink;
    private bool _pauseRequested;
    private bool _abortRequested;
    private int _started;

    public EngraveSession(EngraveMachine machine, PreparedJob job, EngraveSessionOptions? options = null)
        : this(machine, job?.Spec!, options)
    {
        ArgumentNullException.ThrowIfNull(job);
        Job = job;
        _moves = job.Statistics.Moves;
        var idle = new RunProgress(RunState.Idle, 0, job.Statistics.Rows, 0, job.Statistics.BurnRuns, 0, TimeSpan.Zero, TimeSpan.FromSeconds(job.Statistics.EstimatedSeconds), 0, 0, false);
        _progress = new EngraveProgress(RunState.Idle, 1, Passes, 0, _moves, false, idle);
    }

    /// <summary>A session that engraves a drawing: its strokes (docs/vectors.md), the passes, the twin's path check and the log.</summary>
    public EngraveSession(EngraveMachine machine, PreparedDrawing drawing, EngraveSessionOptions? options = null)
        : this(machine, drawing?.Spec!, options)
    {
        ArgumentNullException.ThrowIfNull(drawing);
        Drawing = drawing;
        _moves = drawing.Schedule.Strokes.Count;
        var idle = new RunProgress(RunState.Idle, 0, drawing.Schedule.Strokes.Count, 0, drawing.Plan.Paths.Count, 0, TimeSpan.Zero, TimeSpan.FromSeconds(drawing.Schedule.EstimatedSeconds), 0, 0, false);
        _progress = new EngraveProgress(RunState.Idle, 1, Passes, 0, _moves, false, idle);
    }

    private EngraveSession(EngraveMachine machine, JobSpec spec, EngraveSessionOptions? options)
    {
        ArgumentNullException.ThrowIfNull(machine);
        ArgumentNullException.ThrowIfNull(spec);
        ArgumentOutOfRangeException.ThrowIfLessThan(spec.Passes, 1);
        ArgumentOutOfRangeException.ThrowIfGreaterThan(spec.Passes, JobSpec.MaxPasses);
        Machine = machine;
        Spec = spec;
        Options = options ?? EngraveSessionOptions.Default;

        // Continuing a stopped run finishes the pass that stopped, and only that.
        Passes = Options.ResumeFrom is null ? spec.Passes : 1;
        _progress = new EngraveProgress(RunState.Idle, 1, Passes, 0, 0, false, new RunProgress(RunState.Idle, 0, 0, 0, 0, 0, TimeSpan.Zero, TimeSpan.Zero, 0, 0, false));
    }

    public EngraveMachine Machine { get; }

    /// <summary>The image job; null for a drawing.</summary>
    public PreparedJob? Job { get; }

    /// <summary>The drawing; null for an image job.</summary>
    public PreparedDrawing? Drawing { get; }

    /// <summary>The job's spec (the image's or the drawing's).</summary>
    public JobSpec Spec { get; }

    public EngraveSessionOptions Options { get; }

    /// <summary>The passes this session runs: the job's, or 1 when it continues a stopped run.</summary>
    public int Passes { get; }

    public RunState State
    {
        get
        {
            lock (_lock)
            {
                return _state;
            }
        }
    }

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
            if (_abortRequested || RunStateMachine.IsEnd(_state) || _pauseRequested)
            {
                return;
            }

            _pauseRequested = true;
            current = _current;
        }

        current?.Pause();
        Report(null);
    }

    /// <summary>Continues a paused (or pausing) run.</summary>
    public void Resume()
    {
        RunExecutor? current;
        lock (_lock)
        {
            if (!_pauseRequested)
            {
                return;
            }

            _pauseRequested = false;
            current = _current;
        }

        current?.Resume();
        Report(null);
    }

    /// <summary>Laser off, then the stage stopped; no further pass starts.</summary>
    public void Abort()
    {
        RunExecutor? current;
        lock (_lock)
        {
            if (_abortRequested || RunStateMachine.IsEnd(_state))
            {
                return;
            }

            _abortRequested = true;
            current = _current;

            // Aborting at once, also between passes or before the first: the executor's own Aborting follows.
            if (RunStateMachine.IsLegal(_state, RunState.Aborting))
            {
                _state = RunState.Aborting;
            }
        }

        current?.Abort();
        Report(null);
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

    private async Task<EngraveResult> RunPassesAsync(CancellationToken cancellationToken)
    {
        var time = Machine.TimeProvider;
        var hash = HashOrMissing(Spec.ImagePath);
        var started = Options.WallClock.GetLocalNow();
        var record = (Drawing is { } drawing ? RunRecord.ForDrawing(drawing, hash, started) : RunRecord.ForJob(Job!, hash, started)) with
        {
            Simulated = Machine.Simulated,
            Notes = Options.Notes,
            SampleId = Options.SampleId,
            RepeatOf = Options.RepeatOf,
            Resumed = Options.ResumeFrom is not null,
            Passes = Passes,
        };
        var clockStart = time.GetTimestamp();
        Machine.Inspector?.Begin();
        RunResult? run = null;
        Exception? error = null;
        var passesDone = 0;
        try
        {
            for (var pass = 1; pass <= Passes; pass++)
            {
                var result = await RunPassAsync(pass, cancellationToken);

                // The log speaks for the whole job: times and laser-on add up over the passes, the counts are the last pass's.
                run = run is null ? result : result with
                {
                    StartedAt = run.StartedAt,
                    EngravingDuration = run.EngravingDuration + result.EngravingDuration,
                    EstimatedSeconds = run.EstimatedSeconds + result.EstimatedSeconds,
                    LaserOnSeconds = run.LaserOnSeconds + result.LaserOnSeconds,
                };
                if (result.Outcome != RunOutcome.Completed)
                {
                    break;
                }

                passesDone++;
            }
        }
        catch (Exception ex) when (ex is not OutOfMemoryException)
        {
            // Whatever stopped the run (a preflight refusal, a lost port), the log is still written; the caller reports it.
            error = ex;
        }

        if (Machine.Inspector is { } inspector)
        {
            record = record with { Simulation = Drawing is { } inspected ? inspector.InspectDrawing(inspected) : inspector.Inspect(Job!) };
        }

        record = RunRecords.Complete(record, run, error, Machine.StagePort, Machine.LaserPort, Options.WallClock.GetLocalNow(), time.GetElapsedTime(clockStart)) with
        {
            PassesDone = Passes > 1 ? passesDone : null,
        };
        RunLogFiles? files = null;
        Exception? logError = null;
        if (Options.Log is { } log)
        {
            try
            {
                files = log.Write(record);
            }
            catch (Exception ex) when (ex is RunLogException or IOException or UnauthorizedAccessException)
            {
                logError = ex;
            }
        }

        lock (_lock)
        {
            _current = null;
            _state = RunStateMachine.EndState(record.Outcome);
        }

        Report(null);
        return new EngraveResult(record, run, error, files, logError);
    }

    private async Task<RunResult> RunPassAsync(int pass, CancellationToken cancellationToken)
    {
        var options = new RunOptions { Home = Options.Home && pass == 1, ResumeFrom = pass == 1 ? Options.ResumeFrom : null };
        var executor = Drawing is { } drawing
            ? new RunExecutor(Machine.Stage, Machine.Gate, drawing, Machine.TimeProvider, options)
            : new RunExecutor(Machine.Stage, Machine.Gate, Job!, Machine.TimeProvider, options);
        var movesDone = options.ResumeFrom?.MoveIndex ?? 0;
        executor.MoveCompleted += (_, e) => Interlocked.Exchange(ref movesDone, e.MoveIndex + 1);
        executor.ProgressChanged += (_, p) => Report(new PassProgress(pass, Interlocked.Read(ref movesDone), p));
        bool pause;
        bool abort;
        lock (_lock)
        {
            _current = executor;
            pause = _pauseRequested;
            abort = _abortRequested;
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

        return await executor.RunAsync(cancellationToken);
    }

    private void Report(PassProgress? pass)
    {
        EngraveProgress progress;
        lock (_lock)
        {
            if (RunStateMachine.IsEnd(_state) && pass is not null)
            {
                // A pass's report that comes after the session's end (an abort's, from another thread) changes nothing.
                return;
            }

            if (pass is { } p)
            {
                // A pass's end is not the session's: that comes once every pass has run, the burn is checked and the log written.
                _state = RunStateMachine.IsEnd(p.Run.State) || (_abortRequested && p.Run.State is not RunState.Aborting) ? _state : p.Run.State;
                _progress = new EngraveProgress(_state, p.Pass, Passes, p.MovesDone, _moves, _pauseRequested, p.Run);
            }
            else
            {
                _progress = _progress with { State = _state, PauseRequested = _pauseRequested };
            }

            progress = _progress;
        }

        _sink?.Report(progress);
    }

    private readonly record struct PassProgress(int Pass, long MovesDone, RunProgress Run);
}
