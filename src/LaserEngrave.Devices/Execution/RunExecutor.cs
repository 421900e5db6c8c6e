using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Motion;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Zaber;

using LaserEngrave.Devices.Scheduling;

namespace LaserEngrave.Devices.Execution;

/// <summary>Executes a <see cref="PreparedJob"/>'s plan on a stage and a laser gate, safely, waiting only on a <see cref="TimeProvider"/>.</summary>
/// <remarks>
/// One executor runs one job once (<see cref="RunAsync"/>); to resume after a fault make a new executor with
/// <see cref="RunOptions.ResumeFrom"/>. Events are raised on the run's thread: handlers must be quick and must not block.
/// <see cref="Pause"/>, <see cref="Resume"/> and <see cref="Abort"/> may be called from any thread at any time.
/// The protocol is the one <see cref="PlanEstimator"/> models; docs/execution.md describes it.
/// </remarks>
public sealed partial class RunExecutor
{
    private const string AbortedMessage = "aborted by the operator";

    // Longer than a keepalive's round trip on the gate's line (PING and OK PONG: 13.5 ms at 9600 baud), with a margin.
    private const double KeepAliveQuietSeconds = 0.05;

    private readonly Lock _lock = new();

    // Every laser command goes under this lock, and a switch-on checks for an abort inside it: so once Abort has sent
    // its switch-off, no switch-on can follow it on the wire.
    private readonly AsyncLock _laserLock = new();
    private readonly CancellationTokenSource _abortDone = new();
    private readonly CancellationTokenSource _fault = new();
    private readonly ProcessSettings _process = ProcessSettings.Default;
    private readonly MachineProfile _profile = MachineProfile.Default;
    private TimedSwitching? _timing;
    private readonly int _rowsTotal;
    private readonly long _runsTotal;
    private readonly int _burnSpeedData;
    private readonly int _travelSpeedData;
    private readonly int _accelerationData;
    private RunState _state = RunState.Idle;
    private RunProgress _progress;
    private int _started;
    private bool _abortRequested;
    private bool _pauseRequested;
    private TaskCompletionSource _resumed = NewSignal();
    private Task _abortSequence = Task.CompletedTask;
    private GateKeepAlive? _keepAlive;
    private bool _laserOn;
    private long _laserOnSince;
    private double _laserOnSeconds;
    private bool _laserOffConfirmed = true;
    private string? _laserOffProblem;
    private LaserOffPath? _laserOffBy;

    // A switch-off refused or not acknowledged in time: the laser may still fire, so every path to off is taken at once.
    private bool _switchOffFailed;
    private long _startTimestamp;
    private long _engravingStart;
    private bool _engravingStarted;
    private TimeSpan _notEngraving;
    private long _x;
    private long _y;
    private int _xSpeedData;
    private int _ySpeedData;

    // The move being executed (the first not completed) and the counters over the whole plan.
    private long _moveIndex;
    private int _moveRow;
    private Move? _currentMove;
    private long _currentIndex = -1;
    private bool _stoppedAtKnownPosition;
    private int _rowsDone;
    private int _lastRow = -1;
    private long _runsDone;
    private double _estimateBefore;
    private double _estimateTotal;
    private double _estimatePreparation;
    private long? _resumeX;
    private bool _gateVouchesForCut = true;
    private bool _homed;
    private double _latencyScaleSeen = 1;
    private double _latencyScale = 1;
    private PlanEstimator? _estimator;

    public RunExecutor(IStage stage, ILaserGate gate, PreparedJob job, TimeProvider? timeProvider = null, RunOptions? options = null)
        : this(stage, gate, job?.Spec!, job?.Plan.Geometry.MicrostepUm ?? 0, job?.Plan.Options.Strategy ?? PlanStrategy.Optimized, timeProvider, options)
    {
        ArgumentNullException.ThrowIfNull(job);
        Job = job;
        _timing = job.Plan.Timing;
        _rowsTotal = job.Statistics.Rows;
        _runsTotal = job.Statistics.BurnRuns;
        _progress = new RunProgress(RunState.Idle, 0, _rowsTotal, 0, _runsTotal, 0, TimeSpan.Zero, TimeSpan.FromSeconds(job.Statistics.EngravingSeconds), 0, 0, false);
    }

    /// <summary>An executor for a drawing: its strokes, each axis streaming its speed (docs/vectors.md).</summary>
    public RunExecutor(IStage stage, ILaserGate gate, PreparedDrawing drawing, TimeProvider? timeProvider = null, RunOptions? options = null)
        : this(stage, gate, drawing?.Spec!, drawing?.Schedule.Timing.MicrostepUm ?? 0, PlanStrategy.Optimized, timeProvider, options)
    {
        ArgumentNullException.ThrowIfNull(drawing);
        Drawing = drawing;
        _timing = drawing.Schedule.Timing;
        _rowsTotal = drawing.Schedule.Strokes.Count;
        _runsTotal = drawing.Plan.Paths.Count;
        _progress = new RunProgress(RunState.Idle, 0, _rowsTotal, 0, _runsTotal, 0, TimeSpan.Zero, TimeSpan.FromSeconds(drawing.Schedule.EstimatedSeconds), 0, 0, false);
    }

    private RunExecutor(IStage stage, ILaserGate gate, JobSpec spec, double microstepUm, PlanStrategy strategy, TimeProvider? timeProvider, RunOptions? options)
    {
        ArgumentNullException.ThrowIfNull(stage);
        ArgumentNullException.ThrowIfNull(gate);
        Stage = stage;
        Gate = gate;
        TimeProvider = timeProvider ?? TimeProvider.System;
        Options = options ?? RunOptions.Default;
        _progress = new RunProgress(RunState.Idle, 0, 0, 0, 0, 0, TimeSpan.Zero, TimeSpan.Zero, 0, 0, false);
        if (spec is null)
        {
            return;
        }

        _process = spec.Process;
        _profile = spec.Profile;
        _burnSpeedData = StageUnits.SpeedData(_process.SpeedMmPerS(MoveKind.Burn, strategy), microstepUm);
        _travelSpeedData = StageUnits.SpeedData(_process.SpeedMmPerS(MoveKind.Travel, strategy), microstepUm);
        _accelerationData = StageUnits.AccelerationData(_process.AccelerationMmPerS2, microstepUm);
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
            var (moves, firstIndex) = Drawing is not null ? ([], 0) : Job!.Dots is { } dots ? ([], PrepareDots(dots)) : Prepare();
            var firstStroke = Drawing is null ? 0 : PrepareStrokes();
            _estimatePreparation = Drawing is not null ? EstimateDrawingPreparation(firstStroke)
                : Job!.Dots is { } dotPlan0 ? EstimateDotsPreparation(dotPlan0, firstIndex)
                : EstimatePreparation(moves);
            SetState(RunState.Running);
            _keepAlive = new GateKeepAlive(Gate, GateKeepAlive.PeriodFor(_profile.Gate.WatchdogMs, Options.KeepAliveFraction), TimeProvider, OnKeepAliveFailed);
            using var linked = CancellationTokenSource.CreateLinkedTokenSource(token, _fault.Token);
            if (Drawing is { } drawing)
            {
                await ExecuteVectorAsync(drawing, firstStroke, linked.Token);
            }
            else if (Job!.Dots is { } dotPlan)
            {
                await ExecuteDotsAsync(dotPlan, firstIndex, linked.Token);
            }
            else if (Job.Plan.Timing is not null && _timing is { } timing)
            {
                await ExecuteTimedAsync(moves, firstIndex, timing, linked.Token);
            }
            else
            {
                await ExecuteAsync(moves, firstIndex, linked.Token);
            }

            await SwitchLaserAsync(on: false);
            return await FinishAsync(RunOutcome.Completed, null, identity, startedAt);
        }
        catch (PreflightException) when (!IsAbortRequested)
        {
            await LaserOffSafelyAsync();
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
                ?? (_keepAlive?.Fault is { } keepAliveFault ? $"the laser gate did not answer the keepalive: {keepAliveFault.Message}" : ex.Message);
            return await FailAsync(reason, identity, startedAt);
        }
        finally
        {
            if (_keepAlive is not null)
            {
                await _keepAlive.DisposeAsync();
            }
        }
    }

    /// <summary>Stops after the current burn run with the laser off (state Pausing, then Paused).</summary>
    public void Pause()
    {
        lock (_lock)
        {
            if (_abortRequested || RunStateMachine.IsEnd(_state) || _state is RunState.Paused or RunState.Pausing)
            {
                return;
            }

            _pauseRequested = true;
        }

        if (State is RunState.Running)
        {
            SetState(RunState.Pausing);
        }
    }

    /// <summary>Continues a paused (or pausing) run.</summary>
    public void Resume()
    {
        TaskCompletionSource resumed;
        lock (_lock)
        {
            if (!_pauseRequested)
            {
                return;
            }

            _pauseRequested = false;
            resumed = _resumed;
            _resumed = NewSignal();
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
            if (_abortRequested || RunStateMachine.IsEnd(_state))
            {
                return;
            }

            _abortRequested = true;
            resumed = _resumed;
            _abortSequence = TaskRunner.For(TimeProvider).Start(AbortSequenceAsync);
        }

        SetState(RunState.Aborting);
        resumed.TrySetResult();
    }

    /// <summary>
    /// The latency spread this run assumes, in times the profile's: <see cref="RunOptions.LatencyScale"/>, or more when the
    /// preflight's own exchanges spread wider than the profile says (<see cref="SpreadSeenScale(long)"/>).
    /// </summary>
    private double LatencyScale => _latencyScale;

    /// <summary>
    /// The preflight's stage exchanges (identification, homing's settings and the positions after it: 14 to 22 commands
    /// that reply at once, one at a time) against the profile: their
    /// round trips may spread by the two adapter latencies' jitter, 4 J. Wider, the profile understates the latencies
    /// (or the computer's lateness) and the guards sized by it would let pulses past the edges; the run then assumes
    /// twice the ratio seen, since a dozen draws rarely show the largest. 1 when they fit, or for a plan without timing.
    /// </summary>
    /// <summary>The widest spread a run assumes, in times the profile's (a profile this far off needs `machine latency`).</summary>
    private const double MaxLatencyScale = 8;

    private double SpreadSeenScale(long exchangesBefore)
    {
        if (_timing is null || Stage.X is not ZaberBinaryDevice zaber)
        {
            return 1;
        }

        // Only the identification's, one at a time: during a run replies queue behind one another on the shared wire.
        var connection = zaber.Connection;
        var trips = connection.RecentRoundTripsMs.TakeLast((int)Math.Min(connection.RoundTripsRecorded - exchangesBefore, ZaberConnection.RoundTripsKept)).ToList();
        var allowed = 4 * _timing.StageJitterSeconds * 1000;
        if (trips.Count < 8 || allowed <= 0)
        {
            return 1;
        }

        // A reply held up far beyond the spread (a device busy a moment, a fault) is a doubt for the checks to catch, not a
        // spread to time every edge by. Capped: far wider, the profile is wrong, not the margins.
        trips.Sort();
        var median = trips[trips.Count / 2];
        var spread = trips.Where(t => t <= median + (5 * allowed)).Max() - trips[0];
        return spread <= allowed ? 1 : Math.Min(MaxLatencyScale, 2 * spread / allowed);
    }

    private static TaskCompletionSource NewSignal() => new(TaskCreationOptions.RunContinuationsAsynchronously);

    private static string N(double value) => value.ToString("0.####", CultureInfo.InvariantCulture);

    private bool IsAbortRequested
    {
        get
        {
            lock (_lock)
            {
                return _abortRequested;
            }
        }
    }

    private async Task AbortSequenceAsync()
    {
        try
        {
            await LaserOffSafelyAsync();
            await StopAxesAsync();
        }
        finally
        {
            // Releases whatever the run is waiting for (a move the stop did not interrupt, a pause).
            _abortDone.Cancel();
        }
    }

    private void OnKeepAliveFailed(Exception ex) => _fault.Cancel();

    // ---- preflight ----

    private async Task<MachineIdentity> PreflightAsync(CancellationToken token)
    {
        CheckJob();
        string gateIdentity;
        try
        {
            gateIdentity = await OnceMoreAfterTimeoutAsync(() => Gate.IdentifyAsync(token));
            if (Options.ResumeFrom is { OffByGateWatchdog: true } && !(await Gate.GetStateAsync(token)).WatchdogTripped)
            {
                // The laser's switch-off time counted on the watchdog; a gate restarted since cannot vouch for it.
                _gateVouchesForCut = false;
            }

            await Gate.OffAsync(token);
            await Gate.SetWatchdogAsync(_profile.Gate.WatchdogMs, token);
        }
        catch (DeviceException ex)
        {
            throw new PreflightException($"the laser gate does not answer as it should: {ex.Message}", ex);
        }

        var exchangesBefore = (Stage.X as ZaberBinaryDevice)?.Connection.RoundTripsRecorded ?? 0;
        var x = await IdentifyAxisAsync(Stage.X, "X", token);
        var y = await IdentifyAxisAsync(Stage.Y, "Y", token);
        CheckFirmware(x, "X");
        CheckFirmware(y, "Y");
        CheckReach(x, y);
        // A gate whose watchdog did not trip heard a command that switched the laser off: the cut at the fault's first OFF.
        _resumeX = _gateVouchesForCut ? Options.ResumeFrom?.ResumeXMicrosteps : Options.ResumeFrom?.OffResumeXMicrosteps;
        if (Options.ResumeFrom is { ResumeXMicrosteps: not null, ExpectedXMicrosteps: { } expected })
        {
            // The stage could not be asked when the run stopped: it must be found where its motion was taking it, or the
            // time the laser went off says nothing of where it burned, and the cut-off run is burned again from its start.
            try
            {
                if (!x.IsHomed || await Stage.X.GetPositionAsync(token) != expected)
                {
                    _resumeX = null;
                }
            }
            catch (DeviceException ex)
            {
                throw new PreflightException($"the X axis does not answer: {ex.Message}", ex);
            }
        }

        var homing = new List<Task<long>>();
        try
        {
            // Homing at the process' acceleration and travel speed, so it takes the time the estimate says, not the device's power-up settings'.
            foreach (var (axis, identity) in new[] { (Stage.X, x), (Stage.Y, y) })
            {
                if (Options.Home || !identity.IsHomed)
                {
                    await axis.SetAccelerationAsync(_accelerationData, token);
                    await axis.SetHomeSpeedAsync(_travelSpeedData, token);
                }
            }

            if (Options.Home || !x.IsHomed)
            {
                homing.Add(Stage.X.HomeAsync(token));
            }

            if (Options.Home || !y.IsHomed)
            {
                homing.Add(Stage.Y.HomeAsync(token));
            }

            await Task.WhenAll(homing);
            _homed = homing.Count > 0;
            _x = await Stage.X.GetPositionAsync(token);
            _y = await Stage.Y.GetPositionAsync(token);
        }
        catch (DeviceException ex)
        {
            throw new PreflightException($"homing failed: {ex.Message}", ex);
        }

        // Raster timed switching only: a drawing's schedule and a step-by-step run keep the profile's latencies.
        var scale = Math.Max(double.IsFinite(Options.LatencyScale) ? Math.Max(1, Options.LatencyScale) : 1, SpreadSeenScale(exchangesBefore));
        if (scale > 1 && Drawing is null && Job!.Dots is null && Job.Plan.Timing is { } planned)
        {
            _latencyScale = scale;

            // Guards, margins, run-ups and checks all follow from the latencies' spread: the run times itself with the wider one.
            var latency = _profile.Latency;
            _timing = TimedSwitching.For(_process, _profile with
            {
                Latency = latency with
                {
                    StageJitterMs = latency.StageJitterMs * _latencyScale,
                    GateJitterMs = latency.GateJitterMs * _latencyScale,
                    GateProcessingJitterMs = latency.GateProcessingJitterMs * _latencyScale,
                },
            }, planned.MicrostepUm);
        }

        return new MachineIdentity(x, y, gateIdentity);
    }

    private async Task<AxisIdentity> IdentifyAxisAsync(IStageAxis axis, string name, CancellationToken token)
    {
        AxisIdentity identity;
        try
        {
            identity = await OnceMoreAfterTimeoutAsync(() => axis.IdentifyAsync(token));
            if (identity.AutoReplyDisabled)
            {
                if (!Options.FixAutoReply || axis is not ZaberBinaryDevice zaber)
                {
                    throw new PreflightException(
                        $"the {name} axis (device {axis.DeviceNumber}) has auto-reply disabled (Device Mode bit 0), so it would never confirm a move; clear bit 0 first");
                }

                await zaber.SetDeviceModeAsync(0, ZaberBinaryDevice.AutoReplyDisabledBit, token);
                identity = await axis.IdentifyAsync(token);
            }
        }
        catch (DeviceException ex) when (ex is not PreflightException)
        {
            throw new PreflightException($"the {name} axis (device {axis.DeviceNumber}) does not answer as it should: {ex.Message}", ex);
        }

        return identity;
    }

    /// <summary>Refuses a run whose strategy needs what the axis' firmware does not vouch for (<see cref="ZaberFirmware"/>), naming the axis, the firmware and what is missing.</summary>
    private void CheckFirmware(AxisIdentity identity, string name)
    {
        var drawing = Drawing is not null;
        var timedRaster = !drawing && Job!.Dots is null && Job.Plan.Timing is not null;
        var missing = ZaberFirmware.Missing(identity.FirmwareVersion, speedChangeMidMove: timedRaster, constantSpeed: drawing);
        if (missing.Count > 0)
        {
            var instead = timedRaster ? "; engrave it step by step (--strategy paper), which needs neither" : string.Empty;
            throw new PreflightException(
                $"the {name} axis (device {identity.DeviceNumber}) has firmware {identity.FirmwareText}, for which the Zaber manual does not vouch for {string.Join(" nor ", missing)}, which this job needs (T-series firmware 5.00-5.99 has it){instead}");
        }
    }

    /// <summary>Asks twice before giving up: the first line after a port opens can be lost (a device still waking, noise on the line).</summary>
    private static async Task<T> OnceMoreAfterTimeoutAsync<T>(Func<Task<T>> ask)
    {
        try
        {
            return await ask();
        }
        catch (DeviceTimeoutException)
        {
            return await ask();
        }
    }

    /// <summary>Refuses a job that leaves the travel or asks for speeds the stage cannot run.</summary>
    private void CheckJob()
    {
        if (Drawing is { } drawing)
        {
            CheckDrawing(drawing);
        }
        else if (!Job!.Geometry.FitsTravel)
        {
            var outside = Job.Geometry.Warnings.FirstOrDefault(w => w.Kind == JobWarningKind.OutsideTravel);
            throw new PreflightException(outside?.Message ?? "the job does not fit the stage travel");
        }

        var strategy = Job?.Plan.Options.Strategy ?? PlanStrategy.Optimized;
        var microstepUm = Job?.Plan.Geometry.MicrostepUm ?? _timing!.MicrostepUm;
        if (Job?.EngraveProblem is { } tooShort)
        {
            throw new PreflightException(tooShort);
        }

        CheckSpeed("burn speed", _process.SpeedMmPerS(MoveKind.Burn, strategy));
        CheckSpeed("travel speed", _process.SpeedMmPerS(MoveKind.Travel, strategy));
        var accelerationUnits = Math.Round(StageUnits.MmToMicrosteps(_process.AccelerationMmPerS2, microstepUm) / StageUnits.AccelerationUnitMicrostepsPerS2);
        var maxAcceleration = Math.Min(_profile.X.MaxAccelerationMmPerS2, _profile.Y.MaxAccelerationMmPerS2);
        if (accelerationUnits < 1 || accelerationUnits > StageUnits.MaxSettingData || _process.AccelerationMmPerS2 > maxAcceleration)
        {
            throw new PreflightException(
                $"acceleration {N(_process.AccelerationMmPerS2)} mm/s² is outside what the stage takes ({N(Unit(StageUnits.AccelerationUnitMicrostepsPerS2))}..{N(maxAcceleration)} mm/s²)");
        }

        void CheckSpeed(string what, double mmPerS)
        {
            var units = Math.Round(StageUnits.MmToMicrosteps(mmPerS, microstepUm) / StageUnits.SpeedUnitMicrostepsPerS);
            var max = Math.Min(_profile.X.MaxSpeedMmPerS, _profile.Y.MaxSpeedMmPerS);
            if (units < 1 || units > StageUnits.MaxSettingData || mmPerS > max)
            {
                throw new PreflightException($"{what} {N(mmPerS)} mm/s is outside what the stage takes ({N(Unit(StageUnits.SpeedUnitMicrostepsPerS))}..{N(max)} mm/s)");
            }
        }

        double Unit(double microsteps) => StageUnits.MicrostepsToMm(microsteps, microstepUm);
    }

    /// <summary>Refuses a job that reaches past an axis' Maximum Position (the device's own limit may be below the profile's travel).</summary>
    private void CheckReach(AxisIdentity x, AxisIdentity y)
    {
        if (Drawing is { } drawing)
        {
            CheckDrawingReach(drawing, x, y);
            return;
        }

        var plan = Job!.Plan;
        var geometry = plan.Geometry;
        var right = Math.Min(geometry.EdgeX(geometry.WidthPx) + plan.OverscanMicrosteps, geometry.TravelXMicrosteps);
        var bottom = geometry.EdgeY(geometry.HeightPx);
        foreach (var (name, reach, identity) in new[] { ("X", right, x), ("Y", bottom, y) })
        {
            if (identity.MaximumPosition > 0 && reach > identity.MaximumPosition)
            {
                throw new PreflightException(
                    $"the job reaches {name} = {N(StageUnits.MicrostepsToMm(reach, geometry.MicrostepUm))} mm but the {name} axis stops at {N(StageUnits.MicrostepsToMm(identity.MaximumPosition, geometry.MicrostepUm))} mm (its Maximum Position)");
            }
        }
    }

    // ---- the plan ----

    /// <summary>
    /// Where every execution starts, and where its estimate starts counting: the stop point at the first move (and a row
    /// it is in), then the acceleration and the travel speed set on both axes.
    /// </summary>
    private async Task BeginEngravingAsync(long firstIndex, int row, CancellationToken token)
    {
        lock (_lock)
        {
            _moveIndex = firstIndex;
            _moveRow = row;
        }

        _engravingStart = TimeProvider.GetTimestamp();
        _engravingStarted = true;
        foreach (var axis in new[] { Stage.X, Stage.Y })
        {
            await axis.SetAccelerationAsync(_accelerationData, token);
            await axis.SetTargetSpeedAsync(_travelSpeedData, token);
        }

        (_xSpeedData, _ySpeedData) = (_travelSpeedData, _travelSpeedData);
    }

    private async Task ExecuteAsync(IEnumerable<Move> moves, long firstIndex, CancellationToken token)
    {
        await BeginEngravingAsync(firstIndex, Options.ResumeFrom?.Row ?? 0, token);
        var index = firstIndex;
        var first = true;
        foreach (var move in moves)
        {
            if (first)
            {
                // Reaching the plan's (or the resume point's) first position is not part of the estimate.
                var positioning = TimeProvider.GetTimestamp();
                await MoveToAsync(move.X0, move.Y0, _travelSpeedData, token);
                _notEngraving += TimeProvider.GetElapsedTime(positioning);
                first = false;
            }

            lock (_lock)
            {
                _moveIndex = index;
                _currentIndex = index;
                _moveRow = move.Row;
                _currentMove = move;
            }

            await PauseIfAskedAsync(token);
            await ExecuteMoveAsync(move, token);
            Completed(move, index);
            index++;
        }

        lock (_lock)
        {
            _moveIndex = index;
            _moveRow = Job!.Plan.Mask.Height;
            _currentMove = null;
            if (_lastRow >= 0)
            {
                _rowsDone++;
                _lastRow = -1;
            }
        }
    }

    /// <summary>The moves to execute and the index of the first; for a resumed run also the counters and estimates of what was done before.</summary>
    /// <exception cref="PreflightException">The resume point is not in this job's plan.</exception>
    private (IEnumerable<Move> Moves, long FirstIndex) Prepare()
    {
        var plan = Job!.Plan;
        var microstepUm = plan.Geometry.MicrostepUm;
        var strategy = plan.Options.Strategy;
        _estimator = new PlanEstimator(_process, strategy, microstepUm, _profile.Gate, plan.Timing);
        if (Options.ResumeFrom is not { } resume)
        {
            _estimateTotal = Job.Statistics.EngravingSeconds;
            return (plan.Moves(), 0);
        }

        // A burn run is resumed with its run-up, as it was planned; one cut off midway, from its first pixel not
        // completely burned (the stroke then gets its run-up before that edge).
        var start = resume.MoveIndex;
        long index = 0;
        Move? previous = null;
        Move? trimmed = null;
        foreach (var move in plan.Moves())
        {
            if (index == resume.MoveIndex)
            {
                if (_resumeX is { } x)
                {
                    var dir = Math.Sign(move.X1 - move.X0);
                    if (move.Kind != MoveKind.Burn || (x - move.X0) * dir <= 0 || (move.X1 - x) * dir <= 0)
                    {
                        throw new PreflightException($"the resume point (row {resume.Row}, move {resume.MoveIndex}, X {x}) is not inside a burn run of this job's plan");
                    }

                    trimmed = move with { X0 = x };
                }
                else if (move.Kind == MoveKind.Burn && previous is { Kind: MoveKind.Overscan } runUp && runUp.Row == move.Row)
                {
                    start--;
                }

                break;
            }

            previous = move;
            index++;
        }

        // What was done before the resume point, where its row starts, and the estimate of what is left.
        var before = new PlanEstimator(_process, strategy, microstepUm, _profile.Gate, plan.Timing);
        var remaining = new PlanEstimator(_process, strategy, microstepUm, _profile.Gate, plan.Timing);
        long rowStart = -1;
        index = 0;
        foreach (var move in plan.Moves())
        {
            if (rowStart < 0 && move.Row >= resume.Row)
            {
                rowStart = index;
            }

            if (index < start)
            {
                before.Add(move);
                _runsDone += move.Kind == MoveKind.Burn ? 1 : 0;
                if (move.Row != _lastRow)
                {
                    _rowsDone += _lastRow >= 0 ? 1 : 0;
                    _lastRow = move.Row;
                }
            }
            else
            {
                remaining.Add(move);
            }

            index++;
        }

        remaining.Finish();
        if (start < 0 || start > index || (start < index && (rowStart < 0 || rowStart > start)))
        {
            throw new PreflightException($"the resume point (row {resume.Row}, move {resume.MoveIndex}) is not in this job's plan of {index} moves");
        }

        _estimateBefore = before.ElapsedSeconds - before.StartSeconds;
        _estimateTotal = _estimateBefore + remaining.ElapsedSeconds;
        if (start == index)
        {
            return ([], index);
        }

        var moves = plan.Moves(resume.Row).Skip(checked((int)(start - rowStart)));
        return (trimmed is { } first ? moves.Skip(1).Prepend(first) : moves, start);
    }

    /// <summary>The estimate of what preflight did and the travel to the first move will take, as the plan's figure is made.</summary>
    private double EstimatePreparation(IEnumerable<Move> moves) =>
        Job?.Plan.Timing is { } timing && moves.Take(1).ToList() is [var first]
            ? timing.PreparationSeconds(first.X0, first.Y0, _homed, from: (_x, _y))
            : 0;

    private async Task ExecuteMoveAsync(Move move, CancellationToken token)
    {
        var burn = move.Kind == MoveKind.Burn;

        // Off before anything else, so the laser never stands still on while speeds are set.
        if (!burn && _laserOn)
        {
            await SwitchLaserAsync(on: false);
        }

        // Speeds before switching on, for the same reason (docs/simulator.md: dwell).
        var speedData = burn || move.Kind == MoveKind.Overscan ? _burnSpeedData : _travelSpeedData;
        await SetSpeedsAsync(move.LengthX != 0, move.LengthY != 0, speedData, token);
        if (burn && !_laserOn)
        {
            await SwitchLaserAsync(on: true);
        }

        if (burn)
        {
            // No keepalive in the last moments of the run: a switch-off queued behind one would leave the laser standing on.
            var motion = new TrapezoidProfile(move.LengthX, StageUnits.SpeedMicrostepsPerS(speedData), StageUnits.AccelerationMicrostepsPerS2(_accelerationData));
            var quietAfterSeconds = Math.Max(0, motion.Duration - KeepAliveQuietSeconds);
            _keepAlive!.QuietFrom = TimeProvider.GetTimestamp() + (long)(quietAfterSeconds * TimeProvider.TimestampFrequency);
        }

        await MoveAxesAsync(move.LengthX != 0 ? move.X1 : null, move.LengthY != 0 ? move.Y1 : null, token);
    }

    private async Task MoveToAsync(long x, long y, int speedData, CancellationToken token)
    {
        if (_laserOn)
        {
            await SwitchLaserAsync(on: false);
        }

        await SetSpeedsAsync(x != _x, y != _y, speedData, token);
        await MoveAxesAsync(x != _x ? x : null, y != _y ? y : null, token);
    }

    private async Task SetSpeedsAsync(bool x, bool y, int speedData, CancellationToken token)
    {
        if (x && _xSpeedData != speedData)
        {
            await Stage.X.SetTargetSpeedAsync(speedData, token);
            _xSpeedData = speedData;
        }

        if (y && _ySpeedData != speedData)
        {
            await Stage.Y.SetTargetSpeedAsync(speedData, token);
            _ySpeedData = speedData;
        }
    }

    private async Task MoveAxesAsync(long? x, long? y, CancellationToken token)
    {
        ThrowIfAborted();
        var xMove = x is { } toX ? Stage.X.MoveAbsoluteAsync(toX, token) : null;
        var yMove = y is { } toY ? Stage.Y.MoveAbsoluteAsync(toY, token) : null;
        try
        {
            if (xMove is not null)
            {
                _x = Arrived("X", await xMove, x!.Value);
            }

            if (yMove is not null)
            {
                _y = Arrived("Y", await yMove, y!.Value);
            }
        }
        catch
        {
            // Observe the other axis' move so its failure is not left unobserved.
            foreach (var pending in new[] { xMove, yMove })
            {
                if (pending is not null)
                {
                    _ = pending.ContinueWith(t => t.Exception, CancellationToken.None, TaskContinuationOptions.OnlyOnFaulted, TaskScheduler.Default);
                }
            }

            throw;
        }
    }

    private static long Arrived(string axis, long position, long target) =>
        position == target
            ? position
            : throw new DeviceException($"the {axis} axis reports arriving at {position} instead of {target} microsteps (a garbled reply, or the axis was stopped)");

    private void ThrowIfAborted()
    {
        if (IsAbortRequested)
        {
            throw new OperationCanceledException("aborted");
        }
    }

    private async Task PauseIfAskedAsync(CancellationToken token)
    {
        TaskCompletionSource resumed;
        lock (_lock)
        {
            if (!_pauseRequested || _abortRequested)
            {
                return;
            }

            resumed = _resumed;
        }

        if (_laserOn)
        {
            await SwitchLaserAsync(on: false);
        }

        var pausedAt = TimeProvider.GetTimestamp();
        SetState(RunState.Paused);
        await Signals.WaitAsync(resumed, token);
        _notEngraving += TimeProvider.GetElapsedTime(pausedAt);
        ThrowIfAborted();
        SetState(RunState.Running);
    }

    private void Completed(Move move, long index)
    {
        RunProgress progress;
        lock (_lock)
        {
            _estimator?.Add(move);
            if (move.Kind == MoveKind.Burn)
            {
                _runsDone++;
            }

            if (move.Row != _lastRow)
            {
                _rowsDone += _lastRow >= 0 ? 1 : 0;
                _lastRow = move.Row;
            }

            // The stop point: the first move not done, and a row it is in or after (timed runs complete moves in order,
            // behind the switchings, so the row of the last one done).
            _moveIndex = index + 1;
            _moveRow = move.Row;
            _progress = Snapshot();
            progress = _progress;
        }

        MoveCompleted?.Invoke(this, new MoveCompletedEventArgs(move, index));
        ProgressChanged?.Invoke(this, progress);
    }

    // ---- the laser ----

    private async Task SwitchLaserAsync(bool on)
    {
        await _laserLock.WaitAsync();
        try
        {
            if (on)
            {
                // Inside the lock: an abort's switch-off is either already sent (and we stop here) or comes after this.
                ThrowIfAborted();

                // Gate commands are not cancelled: a reply arriving after a cancelled command would be taken for the next one's.
                await Gate.SetFrequencyAsync(_process.LaserFrequencyWholeHz, CancellationToken.None);
                lock (_lock)
                {
                    _laserOn = true;
                    _laserOnSince = TimeProvider.GetTimestamp();
                }

                // Timed runs feed the watchdog in their own gate schedule, between the timed commands.
                _keepAlive!.Active = _timing is null;
            }
            else
            {
                if (_keepAlive is not null)
                {
                    _keepAlive.Active = false;
                }

                try
                {
                    await Gate.OffAsync(CancellationToken.None);
                }
                catch (DeviceException)
                {
                    MarkSwitchOffFailed();
                    throw;
                }

                MarkLaserOff();
            }
        }
        finally
        {
            _laserLock.Release();
        }
    }

    /// <summary>A switch-off was refused or not acknowledged: the fault's off sequence takes every path at once.</summary>
    private void MarkSwitchOffFailed()
    {
        lock (_lock)
        {
            _switchOffFailed = true;
        }
    }

    private void MarkLaserOff(double leadSeconds = 0)
    {
        lock (_lock)
        {
            if (_laserOn)
            {
                _laserOnSeconds += Math.Max(0, TimeProvider.GetElapsedTime(_laserOnSince).TotalSeconds + leadSeconds);
                _laserOn = false;
            }
        }
    }

    /// <summary>
    /// Switches the laser off after a fault or an abort: OFF, and when that (or an earlier switch-off) was refused or went
    /// unanswered, every other path at once (<see cref="EveryWayOffAsync"/>); records which one the gate confirmed.
    /// </summary>
    private async Task LaserOffSafelyAsync()
    {
        await _laserLock.WaitAsync();
        try
        {
            if (_keepAlive is not null)
            {
                _keepAlive.Active = false;
            }
            bool inDoubt;
            lock (_lock)
            {
                if (_engravingStarted)
                {
                    _faultOffWrite ??= RunSeconds;
                }

                // Every path was taken once already: the laser is confirmed off, or its port is closed and a person must check it.
                if (_laserOffBy is LaserOffPath.OffAgain or LaserOffPath.FrequencyZero or LaserOffPath.None)
                {
                    return;
                }

                inDoubt = _switchOffFailed;
            }

            DeviceException? refused = null;
            Task? first = null;
            if (!inDoubt)
            {
                first = Gate.OffAsync(CancellationToken.None);

                // Answered within its round trip (and the margin a stage reply gets), or it is in doubt: a gate gone deaf
                // must not leave the stage sweeping for the whole of the gate's timeout with the laser on.
                var roundTrip = (_timing?.OffRoundTripSeconds ?? 0.02) + (2 * (_timing?.GateJitterSeconds ?? 0)) + (Options.StallMarginMs / 1000);
                using (var wait = new CancellationTokenSource())
                {
                    await Task.WhenAny(first, PreciseDelay.DelayAsync(TimeProvider, TimeSpan.FromSeconds(roundTrip), wait.Token));
                    wait.Cancel();
                }

                if (first.IsCompletedSuccessfully)
                {
                    MarkLaserOff();
                    lock (_lock)
                    {
                        _laserOffConfirmed = true;
                        _laserOffProblem = null;
                        _laserOffBy = LaserOffPath.Off;
                    }

                    return;
                }

                refused = first.Exception?.InnerException as DeviceException;
            }

            await EveryWayOffAsync(refused, first);
        }
        finally
        {
            _laserLock.Release();
        }
    }

    /// <summary>
    /// A switch-off was refused or went unanswered: OFF again, FREQ 0 and the gate's shortest watchdog go out together,
    /// with a stop to both axes so that nothing more is swept; the first the gate acknowledges of OFF and FREQ 0 confirms
    /// the laser off. When neither is acknowledged the gate's port is closed, so that the gate hears nothing more and its
    /// watchdog switches the laser off, and the run says a person must check the laser. Caller holds the laser lock.
    /// </summary>
    /// <param name="refused">Why the switch-off was refused, when it was.</param>
    /// <param name="first">The fault's own OFF, still waiting for its answer (a late answer confirms the laser off too).</param>
    private async Task EveryWayOffAsync(DeviceException? refused, Task? first)
    {
        // Gate commands are not cancelled (a late reply would be taken for the next one's): each waits its own timeout.
        var off = Gate.OffAsync(CancellationToken.None);
        var zero = Gate.SetFrequencyAsync(0, CancellationToken.None);
        var watchdog = Gate.SetWatchdogAsync(MachineProfileValidator.MinWatchdogMs, CancellationToken.None);
        var stopping = StopAxesAsync();
        await Task.WhenAll(Settled(first ?? Task.CompletedTask), Settled(off), Settled(zero), Settled(watchdog), stopping);
        var path = off.IsCompletedSuccessfully || first?.IsCompletedSuccessfully == true ? LaserOffPath.OffAgain
            : zero.IsCompletedSuccessfully ? LaserOffPath.FrequencyZero
            : LaserOffPath.None;
        MarkLaserOff();
        if (path == LaserOffPath.None && Gate is IAsyncDisposable port)
        {
            // Silence on its line is the one thing left that switches the laser off: the gate's own watchdog.
            await port.DisposeAsync();
        }

        lock (_lock)
        {
            _laserOffBy = path;
            _laserOffConfirmed = path != LaserOffPath.None;
            var why = (refused ?? off.Exception?.InnerException ?? zero.Exception?.InnerException)?.Message;
            _laserOffProblem = path != LaserOffPath.None ? null : string.Create(
                CultureInfo.InvariantCulture,
                $"the laser could not be confirmed off: the gate acknowledged neither OFF nor FREQ 0 ({why}); its port was closed so that its watchdog ({(watchdog.IsCompletedSuccessfully ? MachineProfileValidator.MinWatchdogMs : _profile.Gate.WatchdogMs)} ms) switches the laser off; a person must check the laser");
        }
    }

    private static async Task Settled(Task task)
    {
        try
        {
            await task;
        }
        catch (DeviceException)
        {
            // Looked at through the task itself.
        }
    }

    // ---- the end ----

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

    private async Task<RunResult> FailAsync(string reason, MachineIdentity? identity, DateTimeOffset startedAt)
    {
        await LaserOffSafelyAsync();
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
            await _abortSequence;

            // A move may have been sent in the moment between the abort and the run noticing it: stop again.
            await StopAxesAsync();
        }

        if (outcome == RunOutcome.Completed)
        {
            _estimator?.Finish();
        }

        if (outcome != RunOutcome.Completed)
        {
            await SettleSwitchOnAsync();
        }

        var stopPoint = outcome == RunOutcome.Completed ? null : StopPoint();
        RunResult result;
        lock (_lock)
        {
            var fault = _laserOffProblem is null ? message : message is null ? _laserOffProblem : $"{message}; {_laserOffProblem}";
            var engraving = !_engravingStarted ? TimeSpan.Zero : TimeProvider.GetElapsedTime(_engravingStart) - _notEngraving;
            result = new RunResult
            {
                Outcome = outcome,
                FaultMessage = fault,
                StopPoint = stopPoint,
                Recoverable = outcome == RunOutcome.Failed && _recoverableFault && _laserOffProblem is null && _laserOffConfirmed
                    && stopPoint is { CutPixel: null, ResumeXMicrosteps: null },
                LaserOffConfirmed = _laserOffConfirmed,
                LaserOffBy = outcome == RunOutcome.Completed ? null : _laserOffBy ?? (_laserOffConfirmed ? LaserOffPath.Off : LaserOffPath.None),
                LatencyScale = Math.Max(LatencyScale, _latencyScaleSeen),
                StartedAt = startedAt,
                EndedAt = TimeProvider.GetUtcNow(),
                EngravingDuration = engraving < TimeSpan.Zero ? TimeSpan.Zero : engraving,
                EstimatedSeconds = _estimatePreparation + _estimateTotal - _estimateBefore,
                EstimatedEngravingSeconds = _estimateTotal - _estimateBefore,
                LaserOnSeconds = _laserOnSeconds,
                RowsDone = _rowsDone,
                RowsTotal = _rowsTotal,
                RunsDone = _runsDone,
                RunsTotal = _runsTotal,
                Machine = identity,
            };
        }

        SetState(RunStateMachine.EndState(outcome));
        return result;
    }

    /// <summary>The first move not completed; a move whose stage stopped at its end counts as completed (only its reply was lost).</summary>
    private RunStopPoint StopPoint()
    {
        lock (_lock)
        {
            var index = _moveIndex;
            var row = _moveRow;
            if (_stoppedAtKnownPosition && _currentMove is { } move && _x == move.X1 && _y == move.Y1 && index == _currentIndex)
            {
                index++;
            }

            return CutWithin(new RunStopPoint(row, index, _stoppedAtKnownPosition ? _x : null, _stoppedAtKnownPosition ? _y : null));
        }
    }

    private RunProgress Snapshot()
    {
        var elapsed = TimeProvider.GetElapsedTime(_startTimestamp);
        // Timed runs keep to their estimate (the same timeline), so the clock says how much of it is done.
        var estimateDone = !_engravingStarted ? 0
            : _timing is not null || Job?.Dots is not null ? Math.Min(_estimateTotal - _estimateBefore, (TimeProvider.GetElapsedTime(_engravingStart) - _notEngraving).TotalSeconds)
            : _estimator?.ElapsedSeconds ?? 0;
        var done = _estimateBefore + estimateDone;
        var percent = _estimateTotal > 0 ? Math.Clamp(100 * done / _estimateTotal, 0, 100) : 0;
        var engraving = !_engravingStarted ? 0 : (TimeProvider.GetElapsedTime(_engravingStart) - _notEngraving).TotalSeconds;
        var ratio = estimateDone > 1 && engraving > 0 ? engraving / estimateDone : 1;
        var remaining = Math.Max(0, _estimateTotal - done) * ratio;
        return new RunProgress(_state, _rowsDone, _rowsTotal, _runsDone, _runsTotal, percent, elapsed, TimeSpan.FromSeconds(remaining), _x, _y, _laserOn);
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
                || (_abortRequested && state is not RunState.Aborting && !RunStateMachine.IsEnd(state)))
            {
                return;
            }

            _state = state;
            _progress = Snapshot();
            progress = _progress;
        }

        StateChanged?.Invoke(this, new RunStateChangedEventArgs(previous, state));
        ProgressChanged?.Invoke(this, progress);
    }
}
