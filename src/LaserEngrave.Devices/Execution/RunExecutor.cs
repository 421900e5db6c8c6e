using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Motion;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Programs;
using LaserEngrave.Core.Vectors;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Zaber;

using LaserEngrave.Devices.Scheduling;
using LaserEngrave.Wire.Scheduling;

namespace LaserEngrave.Devices.Execution;

/// <summary>Executes a <see cref="PreparedJob"/>'s plan on a stage and a laser gate, safely, waiting only on a <see cref="TimeProvider"/>.</summary>
/// <remarks>
/// One executor runs one job once (<see cref="RunAsync"/>); to resume after a fault make a new executor with
/// <see cref="RunOptions.ResumeFrom"/>. Events are raised on the run's thread: handlers must be quick and must not block.
/// <see cref="Pause"/>, <see cref="Resume"/> and <see cref="Abort"/> may be called from any thread at any time.
/// The protocol is the one <see cref="PlanEstimator"/> models; docs/execution.md describes it.
/// </remarks>
public sealed partial class RunExecutor : ILaserSafetyRun, IReplyWatchRun
{
    internal const string AbortedMessage = "aborted by the operator";

    // Longer than a keepalive's round trip on the gate's line (PING and OK PONG: 13.5 ms at 9600 baud), with a margin.
    private const double KeepAliveQuietSeconds = 0.05;

    private readonly Lock _lock = new();
    private readonly CancellationTokenSource _abortDone = new();
    private readonly CancellationTokenSource _fault = new();
    private readonly ProcessSettings _process = ProcessSettings.Default;
    private readonly MachineProfile _profile = MachineProfile.Default;
    private TimedSwitching? _timing;

    // The gate's timing for a run without a timing model of its own (step by step, dots): its switch-offs' round trip.
    private TimedSwitching? _gateTiming;

    // The part's program as planned: what the run sends (a timed raster re-timed by the run's own timing model), estimates and checks.
    private readonly PartProgram _program;
    private RunState _state = RunState.Idle;
    private RunProgress _progress;
    private int _started;

    // The run's phase and what was asked of it (pause, abort): held once, shared with the session that runs this pass.
    private readonly RunControl _control;

    // The abort's off sequence once this executor was told of the abort: from then on the run only goes towards its end.
    private Task? _abortSequence;

    // The laser: its lock, keepalive, state and off sequence.
    private readonly LaserSafety _laser;

    // The replies a timed run does not wait for, each watched against its deadline.
    private readonly ReplyWatch _replies;

    // The run's clock: when it started, when the engraving started, and the pauses and positioning that are not engraving.
    private long _startTimestamp;
    private long _engravingStart;
    private bool _engravingStarted;
    private TimeSpan _notEngraving;
    private long _x;
    private long _y;
    private int _xSpeedData;
    private int _ySpeedData;

    // Whether both axes said where they stopped after a fault or an abort (the stop point's position).
    private bool _stoppedAtKnownPosition;

    // The count of moves, rows and runs done, and the estimate: what progress, the stop point and the log read.
    private readonly RunAccounting _accounting;

    // What preflight found (RunPreflight) and what the run saw of the latencies' spread since.
    private long? _resumeX;
    private bool _homed;
    private double _latencyScaleSeen = 1;
    private double _latencyScale = 1;

    /// <summary>An executor for one image (raster or dots) or one drawing: it runs that job's plan once.</summary>
    /// <remarks>Layers and passes are the session's (<see cref="EngraveSession"/>, one executor a pass of a layer); a sweep's cells are each a job.</remarks>
    public RunExecutor(IStage stage, ILaserGate gate, EngraveJob job, TimeProvider? timeProvider = null, RunOptions? options = null)
        : this(stage, gate, job, timeProvider, options, new RunControl())
    {
    }

    /// <summary>An executor for one pass of a session, acting on the session's <paramref name="control"/> (its pause and abort requests).</summary>
    internal RunExecutor(IStage stage, ILaserGate gate, EngraveJob job, TimeProvider? timeProvider, RunOptions? options, RunControl control)
    {
        ArgumentNullException.ThrowIfNull(stage);
        ArgumentNullException.ThrowIfNull(gate);
        ArgumentNullException.ThrowIfNull(job);
        ArgumentNullException.ThrowIfNull(control);
        _control = control;
        Stage = stage;
        Gate = gate;
        TimeProvider = timeProvider ?? TimeProvider.System;
        Options = options ?? RunOptions.Default;

        // The one place the executor tells the kinds apart: the program it runs; from here on the program's type answers.
        (Job, Drawing, _program) = job switch
        {
            RasterJob raster => (raster.Prepared, (PreparedDrawing?)null, (PartProgram)raster.Prepared.Program()),
            DotJob dots => (dots.Prepared, null, dots.Program()),
            DrawingJob drawing => (null, drawing.Drawing, drawing.Program()),
            LayersJob or SweepJob => throw new ArgumentException("an executor runs one image or drawing: a job of layers runs through EngraveSession, a sweep through SweepSession", nameof(job)),
            _ => throw new ArgumentException($"unknown job kind {job.GetType().Name}", nameof(job)),
        };

        // The timing model the run starts from: a timed raster's or the drawing's (dots and step by step keep none).
        _timing = _program switch
        {
            RasterProgram raster => raster.Timing,
            DrawingProgram drawing => drawing.Timing,
            _ => null,
        };
        _progress = IdleProgress(job);
        _accounting = new RunAccounting(_progress.RowsTotal, _progress.RunsTotal);
        var spec = job.Spec;
        _process = spec.Process;
        _profile = spec.Profile;
        _laser = new LaserSafety(Gate, TimeProvider, _process.LaserFrequencyWholeHz, _profile.Gate.WatchdogMs, Options.StallMarginMs, this) { GateNeverReplies = _profile.Gate.NeverReplies };
        _replies = new ReplyWatch(TimeProvider, Options.StallMarginMs, this) { Arriving = gate => gate ? Gate.IsReceiving : Stage.IsReceiving, Written = gate => gate ? Gate.LineWritten : Stage.LineWritten };
    }

    /// <summary>What a run of a single image or drawing shows before it starts: its rows (strokes) and burn runs (paths) to do, and its estimate.</summary>
    /// <remarks>
    /// The totals are the job's <see cref="EngraveJob.Planned"/>, the count its log keeps and Continue checks: a drawing's
    /// paths too short to burn are not paths to do, so a completed run ends with every run counted done.
    /// </remarks>
    internal static RunProgress IdleProgress(EngraveJob job)
    {
        var seconds = job switch
        {
            RasterJob { Prepared.Statistics: var s } => s.EngravingSeconds,
            DotJob { Prepared.Statistics: var s } => s.EngravingSeconds,
            DrawingJob { Drawing: var d } => d.Schedule.EstimatedSeconds,
            _ => throw new ArgumentException($"an executor runs one image or drawing, not a {job.GetType().Name}", nameof(job)),
        };
        var (units, runs) = job.Planned;
        return new RunProgress(RunState.Idle, 0, units, 0, runs, 0, TimeSpan.Zero, TimeSpan.FromSeconds(seconds), 0, 0, false);
    }

    /// <summary>Raised on every state change.</summary>
    public event EventHandler<RunStateChangedEventArgs>? StateChanged;

    /// <summary>Raised after every move and on every state change.</summary>
    public event EventHandler<RunProgress>? ProgressChanged;

    /// <summary>Raised after every move of the plan, with the move.</summary>
    public event EventHandler<MoveCompletedEventArgs>? MoveCompleted;

    public IStage Stage { get; }

    public ILaserGate Gate { get; }

    /// <summary>The image job this executor runs; null for a drawing.</summary>
    public PreparedJob? Job { get; }

    /// <summary>The drawing this executor runs; null for an image job.</summary>
    public PreparedDrawing? Drawing { get; }

    public TimeProvider TimeProvider { get; }

    public RunOptions Options { get; }

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

    /// <summary>The latest progress snapshot.</summary>
    public RunProgress Progress
    {
        get
        {
            lock (_lock)
            {
                return _progress;
            }
        }
    }

    /// <summary>Preflight, then the plan; returns how it ended (completed, aborted or failed: faults do not throw).</summary>
    /// <param name="cancellationToken">Cancelling it aborts the run (laser off, then the stage stopped), as <see cref="Abort"/>.</param>
    /// <exception cref="PreflightException">Preflight refused to start; nothing moved under the laser.</exception>
    public async Task<RunResult> RunAsync(CancellationToken cancellationToken)
    {
        if (Interlocked.Exchange(ref _started, 1) != 0)
        {
            throw new InvalidOperationException("a RunExecutor runs once; make a new one (with RunOptions.ResumeFrom to continue)");
        }

        var startedAt = TimeProvider.GetUtcNow();
        _startTimestamp = TimeProvider.GetTimestamp();
        await using var registration = cancellationToken.Register(Abort);
        var token = _abortDone.Token;
        MachineIdentity? identity = null;
        try
        {
            SetState(RunState.Preflight);
            identity = await PreflightAsync(token);
            // One motion strategy per kind of program, chosen once: strokes (RunExecutor.Vector), dots (.Dots), timed
            // switching (.Timed) or step by step (.StepByStep); each first counts what a resumed run did before.
            Func<CancellationToken, Task> motion = _program switch
            {
                DrawingProgram drawing => PrepareStrokes(drawing),
                DotProgram dots => PrepareDots(dots),
                RasterProgram raster => Prepare(raster),
                _ => throw new InvalidOperationException($"unknown program {_program.GetType().Name}"),
            };

            SetState(RunState.Running);
            _laser.StartKeepAlive(GateKeepAlive.PeriodFor(_profile.Gate.WatchdogMs, Options.KeepAliveFraction), whileOn: _timing is null, OnKeepAliveFailed);
            using var linked = CancellationTokenSource.CreateLinkedTokenSource(token, _fault.Token);
            await motion(linked.Token);

            await _laser.SwitchAsync(on: false);
            return await FinishAsync(RunOutcome.Completed, null, identity, startedAt);
        }
        catch (PreflightException) when (!IsAbortRequested)
        {
            await _laser.OffSafelyAsync();
            SetState(RunState.Failed);
            throw;
        }
        catch (Exception ex)
        {
            // Whatever went wrong (a device, or a bug), the laser goes off and the stage stops before anything else.
            if (IsAbortRequested)
            {
                return await FinishAsync(RunOutcome.Aborted, AbortedMessage, identity, startedAt);
            }

            var reason = _timedFault
                ?? (_laser.KeepAlive?.Fault is { } keepAliveFault ? $"the laser gate did not answer the keepalive: {keepAliveFault.Message}" : ex.Message);
            return await FailAsync(reason, identity, startedAt);
        }
        finally
        {
            await _laser.DisposeAsync();
        }
    }

    /// <summary>Stops after the current burn run with the laser off (state Pausing, then Paused).</summary>
    public void Pause()
    {
        lock (_lock)
        {
            if (_abortSequence is not null || RunStateMachine.IsEnd(_state) || _state is RunState.Paused or RunState.Pausing || !_control.RequestPause())
            {
                return;
            }
        }

        if (State is RunState.Running)
        {
            SetState(RunState.Pausing);
        }
    }

    /// <summary>Continues a paused (or pausing) run.</summary>
    public void Resume()
    {
        var resumed = _control.RequestResume();
        if (resumed is null)
        {
            return;
        }

        if (State is RunState.Pausing)
        {
            SetState(RunState.Running);
        }

        resumed.TrySetResult();
    }

    /// <summary>Switches the laser off, then stops both axes; wins over everything else, from any thread, at any time.</summary>
    public void Abort()
    {
        TaskCompletionSource resumed;
        lock (_lock)
        {
            if (_abortSequence is not null || RunStateMachine.IsEnd(_state))
            {
                return;
            }

            resumed = _control.RequestAbort();
            _abortSequence = TaskRunner.For(TimeProvider).Start(AbortSequenceAsync);
        }

        SetState(RunState.Aborting);
        resumed.TrySetResult();
    }

    /// <summary>
    /// The latency spread this run assumes, in times the profile's: <see cref="RunOptions.LatencyScale"/>, or more when the
    /// preflight's own exchanges spread wider than the profile says (<see cref="RunPreflight"/>).
    /// </summary>
    private double LatencyScale => _latencyScale;

    /// <summary>The widest spread a run assumes, in times the profile's (a profile this far off needs `machine latency`).</summary>
    private const double MaxLatencyScale = RunPreflight.MaxLatencyScale;

    private static string N(double value) => value.ToString("0.####", CultureInfo.InvariantCulture);

    /// <summary>Preflight, once (<see cref="RunPreflight"/>): the run starts from what it found.</summary>
    private async Task<MachineIdentity> PreflightAsync(CancellationToken token)
    {
        var preflight = new RunPreflight(Stage, Gate, _program, Job, Drawing, _process, _profile, _timing, _program.Motion.TravelSpeedData, _program.Motion.AccelerationData, Options);
        var found = await preflight.RunAsync(token);
        _resumeX = found.ResumeX;
        _homed = found.Homed;
        _x = found.X;
        _y = found.Y;
        _latencyScale = found.LatencyScale;
        _timing = found.Timing;
        _scheduledBursts = found.ScheduledBursts;
        return found.Identity;
    }

    private bool IsAbortRequested
    {
        get
        {
            lock (_lock)
            {
                return _abortSequence is not null;
            }
        }
    }

    private void ThrowIfAborted()
    {
        if (IsAbortRequested)
        {
            throw new OperationCanceledException("aborted");
        }
    }

    private async Task PauseIfAskedAsync(CancellationToken token)
    {
        TaskCompletionSource? resumed;
        lock (_lock)
        {
            resumed = _abortSequence is null ? _control.PauseSignal() : null;
        }

        if (resumed is null)
        {
            return;
        }

        if (_laser.On)
        {
            await _laser.SwitchAsync(on: false);
        }

        var pausedAt = TimeProvider.GetTimestamp();
        SetState(RunState.Paused);
        await Signals.WaitAsync(resumed, token);
        _notEngraving += TimeProvider.GetElapsedTime(pausedAt);
        ThrowIfAborted();
        SetState(RunState.Running);
    }

    private async Task<RunResult> FailAsync(string reason, MachineIdentity? identity, DateTimeOffset startedAt)
    {
        await _laser.OffSafelyAsync();
        await StopAxesAsync();
        if (IsAbortRequested)
        {
            return await FinishAsync(RunOutcome.Aborted, AbortedMessage, identity, startedAt);
        }

        return await FinishAsync(RunOutcome.Failed, reason, identity, startedAt);
    }

    private async Task<RunResult> FinishAsync(RunOutcome outcome, string? message, MachineIdentity? identity, DateTimeOffset startedAt)
    {
        if (outcome == RunOutcome.Aborted)
        {
            // Through Aborting even when the run noticed the abort before Abort() had set it: the table's only way to Aborted.
            SetState(RunState.Aborting);
            await (_abortSequence ?? Task.CompletedTask);

            // A move may have been sent in the moment between the abort and the run noticing it: stop again.
            await StopAxesAsync();
        }

        if (outcome == RunOutcome.Completed)
        {
            _accounting.Finish();
        }

        if (outcome != RunOutcome.Completed)
        {
            await SettleSwitchOnAsync();
        }

        var stopPoint = outcome == RunOutcome.Completed ? null : StopPoint();
        RunResult result;
        lock (_lock)
        {
            var (offConfirmed, offProblem, offBy) = _laser.OffState;
            var fault = offProblem is null ? message : message is null ? offProblem : $"{message}; {offProblem}";
            var engraving = !_engravingStarted ? TimeSpan.Zero : TimeProvider.GetElapsedTime(_engravingStart) - _notEngraving;
            result = new RunResult
            {
                Outcome = outcome,
                FaultMessage = fault,
                StopPoint = stopPoint,
                Recoverable = outcome == RunOutcome.Failed && _recoverableFault && offProblem is null && offConfirmed
                    && stopPoint is { CutPixel: null, ResumeXMicrosteps: null },
                LaserOffConfirmed = offConfirmed,
                LaserOffBy = outcome == RunOutcome.Completed ? null : offBy ?? (offConfirmed ? LaserOffPath.Off : LaserOffPath.None),
                LatencyScale = Math.Max(LatencyScale, _latencyScaleSeen),
                GuardScale = LatencyScale,
                StartedAt = startedAt,
                EndedAt = TimeProvider.GetUtcNow(),
                EngravingDuration = engraving < TimeSpan.Zero ? TimeSpan.Zero : engraving,
                EstimatedSeconds = _accounting.EstimatePreparation + _accounting.EstimateTotal - _accounting.EstimateBefore,
                EstimatedEngravingSeconds = _accounting.EstimateTotal - _accounting.EstimateBefore,
                LaserOnSeconds = _laser.OnSeconds,
                LateSwitches = _lateSwitches,
                BurstEndedItself = _burstEndedItself,
                RowsDone = _accounting.RowsDone,
                RowsTotal = _accounting.RowsTotal,
                RunsDone = _accounting.RunsDone,
                RunsTotal = _accounting.RunsTotal,
                Machine = identity,
            };
        }

        SetState(RunStateMachine.EndState(outcome));
        return result;
    }

    private void SetState(RunState state)
    {
        RunState previous;
        RunProgress progress;
        lock (_lock)
        {
            previous = _state;
            // Only the table's transitions; once an abort is asked, only towards its end.
            if (!RunStateMachine.IsLegal(previous, state)
                || (_abortSequence is not null && state is not RunState.Aborting && !RunStateMachine.IsEnd(state)))
            {
                return;
            }

            _state = state;
            _control.Entered(state);
            _progress = Snapshot();
            progress = _progress;
        }

        StateChanged?.Invoke(this, new RunStateChangedEventArgs(previous, state));
        ProgressChanged?.Invoke(this, progress);
    }

    TimedSwitching ILaserSafetyRun.Timing => _timing ?? (_gateTiming ??= TimedSwitching.For(_process, _profile, _profile.X.MicrostepUm));

    double ILaserSafetyRun.GateQueueSeconds => GateQueueSeconds();

    void ILaserSafetyRun.ThrowIfAborted() => ThrowIfAborted();

    void ILaserSafetyRun.OffSequenceStarting(bool? inDoubt)
    {
        lock (_lock)
        {
            // When the fault's switch-off left: a burn run cut by it is burned up to there (the stop point's cut pixel).
            if (_engravingStarted)
            {
                _cut.FaultOffSent(RunSeconds);
            }

            // A switch-off refused or unanswered after the burn run's burst had stopped the laser by itself: the run's
            // last pulse was the burst's, inside the run; the paths to off still go, and say which confirmed it.
            if (inDoubt == true && double.IsFinite(_burstEndsAt))
            {
                _burstEndedItself |= RunSeconds >= _burstEndsAt;
            }
        }
    }

    Task ILaserSafetyRun.StopStageAsync() => StopAxesAsync();

    double IReplyWatchRun.RunSeconds => RunSeconds;

    TimedSwitching? IReplyWatchRun.Timing => _timing;

    DeviceException IReplyWatchRun.Fault(string reason, bool recoverable) => Fault(reason, recoverable);

    void IReplyWatchRun.SwitchOffFailed(Task reply) => _laser.MarkSwitchOffFailed(reply);

    /// <summary>An abort: the laser off first, then the stage stopped.</summary>
    private async Task AbortSequenceAsync()
    {
        try
        {
            await _laser.OffSafelyAsync();
            await StopAxesAsync();
        }
        finally
        {
            // Releases whatever the run is waiting for (a move the stop did not interrupt, a pause).
            _abortDone.Cancel();
        }
    }

    private void OnKeepAliveFailed(Exception ex) => _fault.Cancel();

    /// <summary>Stops both axes and records where they stopped (when they say); a stage gone silent leaves the stop point without a position.</summary>
    private async Task StopAxesAsync()
    {
        var known = true;
        foreach (var axis in new[] { Stage.X, Stage.Y })
        {
            try
            {
                var written = _engravingStarted ? RunSeconds : double.NaN;
                var position = await axis.StopAsync(CancellationToken.None);
                if (axis == Stage.X)
                {
                    NoteStopped(written, position);
                }

                lock (_lock)
                {
                    if (axis == Stage.X)
                    {
                        _x = position;
                    }
                    else
                    {
                        _y = position;
                    }
                }
            }
            catch (DeviceException)
            {
                // The stage may be gone (port lost, silent): the stop point then has no position.
                known = false;
            }
        }

        lock (_lock)
        {
            _stoppedAtKnownPosition = known;
        }
    }

    /// <summary>A move of the plan completed: counted (<see cref="RunAccounting"/>), then reported.</summary>
    private void Completed(Move move, long index)
    {
        RunProgress progress;
        lock (_lock)
        {
            _accounting.Completed(move, index);
            _progress = Snapshot();
            progress = _progress;
        }

        MoveCompleted?.Invoke(this, new MoveCompletedEventArgs(move, index));
        ProgressChanged?.Invoke(this, progress);
    }

    /// <summary>The stop point: the first move not completed, where the stage stopped, and a timed run's cut pixel.</summary>
    private RunStopPoint StopPoint()
    {
        lock (_lock)
        {
            return CutWithin(_accounting.StopPoint(_stoppedAtKnownPosition ? (_x, _y) : null));
        }
    }

    /// <summary>A progress snapshot; caller holds the lock.</summary>
    private RunProgress Snapshot()
    {
        var elapsed = TimeProvider.GetElapsedTime(_startTimestamp);
        double? engraving = _engravingStarted ? (TimeProvider.GetElapsedTime(_engravingStart) - _notEngraving).TotalSeconds : null;

        // Timed runs and dots keep to their estimate (the same timeline), so the clock says how much of it is done.
        return _accounting.Snapshot(_state, elapsed, engraving, byClock: _timing is not null || _program is DotProgram, _x, _y, _laser.On);
    }
}
