using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Sweeps;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Wire.Scheduling;

namespace LaserEngrave.Devices.Execution;

/// <summary>What a <see cref="SweepSession"/> is doing: which job of the sweep (the labels count as one), and that job's progress.</summary>
/// <param name="Index">The job under way, from 0 (the labels first when there are labels, then the cells row by row).</param>
/// <param name="Jobs">The sweep's jobs.</param>
/// <param name="Cell">The cell under way; null while the labels burn.</param>
/// <param name="Run">The job's own progress.</param>
public sealed record SweepProgress(int Index, int Jobs, SweepCell? Cell, EngraveProgress Run);

/// <summary>One job of a sweep has ended: the cell (null for the labels) and how it ended, with the simulator's burn check when there is one.</summary>
public sealed class SweepJobEndedEventArgs(SweepCell? cell, EngraveResult result) : EventArgs
{
    public SweepCell? Cell { get; } = cell;

    public EngraveResult Result { get; } = result;
}

/// <summary>How a sweep ended: its record (written or not) and where it went.</summary>
public sealed record SweepResult(SweepRecord Record, RunLogFiles? Files, Exception? LogError)
{
    public bool Completed => Record.Outcome == RunOutcome.Completed;
}

/// <summary>Options of a sweep run, as of an engraving.</summary>
public sealed record SweepSessionOptions
{
    public string? Notes { get; init; }

    public string? SampleId { get; init; }

    /// <summary>Home both axes before the first job even if they are homed.</summary>
    public bool Home { get; init; }

    /// <summary>The person accepts a laser gate without a watchdog for every cell (<see cref="EngraveSessionOptions.AcceptNoWatchdog"/>).</summary>
    public bool AcceptNoWatchdog { get; init; }

    public ISweepLogWriter? Log { get; init; }

    public TimeProvider WallClock { get; init; } = TimeProvider.System;
}

/// <summary>
/// A parameter sweep in one run: the labels, then every cell, each an <see cref="EngraveSession"/> (its passes, its
/// burn check on the simulator) on the same machine, one after the other; then one log with every cell.
/// </summary>
/// <remarks>
/// A job that does not complete ends the sweep with the laser off (as its session leaves it); the cells after it are
/// logged as not run. <see cref="Abort"/> may be called from any thread at any time. A session runs once.
/// </remarks>
public sealed class SweepSession
{
    private readonly Lock _lock = new();
    private EngraveSession? _current;
    private FocusAxis? _focusMoving;
    private bool _abortRequested;
    private int _started;

    public SweepSession(EngraveMachine machine, SweepPlan plan, SweepSessionOptions? options = null)
    {
        ArgumentNullException.ThrowIfNull(machine);
        ArgumentNullException.ThrowIfNull(plan);
        Machine = machine;
        Plan = plan;
        Options = options ?? new SweepSessionOptions();
    }

    /// <summary>Raised after each job (labels or cell), on the run's thread: keep it quick.</summary>
    public event EventHandler<SweepJobEndedEventArgs>? JobEnded;

    public EngraveMachine Machine { get; }

    public SweepPlan Plan { get; }

    public SweepSessionOptions Options { get; }

    /// <summary>Runs the labels and every cell on the machine's own runner, then writes the sweep's log.</summary>
    public Task<SweepResult> RunAsync(IProgress<SweepProgress>? progress, CancellationToken cancellationToken)
    {
        if (Interlocked.Exchange(ref _started, 1) != 0)
        {
            throw new InvalidOperationException("a SweepSession runs once; make a new one");
        }

        return TaskRunner.For(Machine.TimeProvider).Run(() => RunJobsAsync(progress, cancellationToken));
    }

    /// <summary>Where the cell under way puts the stage at <paramref name="timestamp"/> (of the machine's clock) by its engine's own timing (<see cref="EngraveSession.StrokePositionAt"/>); null otherwise.</summary>
    public StrokePosition? StrokePositionAt(long timestamp)
    {
        EngraveSession? current;
        lock (_lock)
        {
            current = _current;
        }

        return current?.StrokePositionAt(timestamp);
    }

    /// <summary>Laser off, then the stage stopped (the focus axis too, when it is moving); no further cell starts.</summary>
    public void Abort()
    {
        EngraveSession? current;
        FocusAxis? focus;
        lock (_lock)
        {
            _abortRequested = true;
            current = _current;
            focus = _focusMoving;
        }

        current?.Abort();
        if (focus is not null)
        {
            _ = TaskRunner.For(Machine.TimeProvider).Start(focus.StopAsync);
        }
    }

    /// <summary>
    /// The cells this computer cannot hold with this gate (<see cref="SpeedHold"/>), named before the first cell, not when
    /// the run reaches them. The gate is asked whether it times its switch-ons (CAPS?) only when that decides it, so a
    /// sweep within what any gate holds sends nothing more.
    /// </summary>
    private async Task<string?> SpeedsNotHeldAsync(CancellationToken cancellationToken)
    {
        var profile = Plan.Spec.Profile;
        var hostTimed = SweepSpeedHold.Problem(Plan.Cells, profile, scheduled: false);
        if (hostTimed is null || !profile.Gate.CountsBursts)
        {
            return hostTimed;
        }

        try
        {
            var scheduled = (await Machine.Gate.GetCapabilitiesAsync(cancellationToken)).Contains(LaserGateCapabilities.After);
            return scheduled ? SweepSpeedHold.Problem(Plan.Cells, profile, scheduled: true) : hostTimed;
        }
        catch (DeviceException)
        {
            // The first cell's preflight asks the gate again and says what is wrong with it.
            return null;
        }
    }

    private async Task<SweepResult> RunJobsAsync(IProgress<SweepProgress>? progress, CancellationToken cancellationToken)
    {
        await using var registration = cancellationToken.Register(Abort);
        var startedAt = Options.WallClock.GetLocalNow();
        var jobs = new List<(SweepCell? Cell, PreparedJob Job)>();
        if (Plan.Labels is { } labelsJob)
        {
            jobs.Add((null, labelsJob));
        }

        jobs.AddRange(Plan.Cells.Select(c => ((SweepCell?)c, c.Job)));
        var tally = new SweepTally();
        var focus = OpenFocus(tally);
        if (tally.Fault is null && await SpeedsNotHeldAsync(cancellationToken) is { } tooFast)
        {
            tally.End(RunOutcome.Refused, tooFast);
        }

        for (var i = 0; tally.Fault is null && i < jobs.Count; i++)
        {
            if (!await RunJobAsync(i, jobs, focus, tally, progress, cancellationToken))
            {
                break;
            }
        }

        // Back to the visible focus once every cell is burned, so the next job is not burned out of focus.
        if (focus is not null && tally.Outcome == RunOutcome.Completed)
        {
            try
            {
                await MoveFocusAsync(focus, Plan.Spec.Profile.Z!.MicrostepsAt(0), cancellationToken);
            }
            catch (Exception ex) when (ex is DeviceException or OperationCanceledException)
            {
                tally.Fault = $"every cell was burned, but the focus could not be moved back to z.focusMm: {ex.Message}";
            }
        }

        var record = NewRecord(tally, startedAt);
        RunLogFiles? files = null;
        Exception? logError = null;
        if (Options.Log is { } log)
        {
            try
            {
                files = log.WriteSweep(record);
            }
            catch (Exception ex) when (ex is RunLogException or IOException or UnauthorizedAccessException)
            {
                logError = ex;
            }
        }

        return new SweepResult(record, files, logError);
    }

    /// <summary>What the sweep has run so far: each cell's log, the Z each reached, the labels' log, and how it ends.</summary>
    private sealed class SweepTally
    {
        public Dictionary<SweepCell, RunRecord> Runs { get; } = [];

        public Dictionary<SweepCell, long> ReachedZ { get; } = [];

        public RunRecord? Labels { get; set; }

        public RunOutcome Outcome { get; set; } = RunOutcome.Completed;

        public string? Fault { get; set; }

        public void End(RunOutcome outcome, string fault) => (Outcome, Fault) = (outcome, fault);
    }

    /// <summary>The focus axis when a cell has a focus of its own; null without (or when the profile has none, refused).</summary>
    private FocusAxis? OpenFocus(SweepTally tally)
    {
        if (!Plan.Cells.Any(c => c.FocusZMicrosteps is not null))
        {
            return null;
        }

        try
        {
            return new FocusAxis(Machine.Stage, Machine.Gate, Plan.Spec.Profile);
        }
        catch (PreflightException ex)
        {
            tally.End(RunOutcome.Refused, ex.Message);
            return null;
        }
    }

    /// <summary>Runs job <paramref name="i"/> (the labels or a cell) at its focus, as its own session and log; returns whether the sweep goes on.</summary>
    private async Task<bool> RunJobAsync(int i, List<(SweepCell? Cell, PreparedJob Job)> jobs, FocusAxis? focus, SweepTally tally, IProgress<SweepProgress>? progress, CancellationToken cancellationToken)
    {
        var (cell, job) = jobs[i];
        EngraveSession session;
        lock (_lock)
        {
            if (_abortRequested)
            {
                tally.End(RunOutcome.Aborted, "aborted by the operator");
                return false;
            }

            session = new EngraveSession(Machine, job, new EngraveSessionOptions
            {
                Notes = Options.Notes,
                SampleId = Options.SampleId,
                Home = Options.Home && i == 0,
                AcceptNoWatchdog = Options.AcceptNoWatchdog,
                ImageSha256 = SweepPlan.MaskSha256(job.Mask),
                WallClock = Options.WallClock,
            });
            _current = session;
        }

        // The labels burn at the visible focus, each cell at its own.
        if (focus is not null && (cell is null ? Plan.Spec.Profile.Z!.MicrostepsAt(0) : cell.FocusZMicrosteps) is { } z
            && !await FocusForAsync(focus, cell, z, tally, cancellationToken))
        {
            return false;
        }

        var sink = progress is null ? null : new Relay(p => progress.Report(new SweepProgress(i, jobs.Count, cell, p)));
        var result = await session.RunAsync(sink, cancellationToken);
        lock (_lock)
        {
            _current = null;
        }

        if (cell is null)
        {
            tally.Labels = result.Record;
        }
        else
        {
            tally.Runs[cell] = result.Record;
        }

        JobEnded?.Invoke(this, new SweepJobEndedEventArgs(cell, result));
        if (result.Record.Outcome != RunOutcome.Completed)
        {
            var what = cell?.Describe() ?? "the labels";
            tally.End(result.Record.Outcome, $"{what}: {result.Error?.Message ?? result.Record.Fault?.Message ?? result.Record.Outcome.ToString().ToLowerInvariant()}");
            return false;
        }

        return true;
    }

    /// <summary>Moves the focus to <paramref name="z"/> for a cell (null: the labels); returns false when that failed and the sweep ends.</summary>
    private async Task<bool> FocusForAsync(FocusAxis focus, SweepCell? cell, long z, SweepTally tally, CancellationToken cancellationToken)
    {
        try
        {
            var reached = await MoveFocusAsync(focus, z, cancellationToken);
            if (cell is not null)
            {
                tally.ReachedZ[cell] = reached;
            }

            return true;
        }
        catch (Exception ex) when (ex is DeviceException or OperationCanceledException)
        {
            RunOutcome outcome;
            lock (_lock)
            {
                _current = null;
                outcome = ex is OperationCanceledException || _abortRequested ? RunOutcome.Aborted : RunOutcome.Failed;
            }

            tally.End(outcome, outcome == RunOutcome.Aborted
                ? $"aborted by the operator while moving the focus to {z} microsteps for {cell?.Describe() ?? "the labels"}"
                : $"{cell?.Describe() ?? "the labels"}: moving the focus to {z} microsteps: {ex.Message}");

            // A device that failed mid-move (a lost reply) may still be moving: laser off and Z stopped before the log.
            await focus.StopAsync();
            return false;
        }
    }

    /// <summary>The sweep's log: its grid, and each cell's size, focus and run.</summary>
    private SweepRecord NewRecord(SweepTally tally, DateTimeOffset startedAt)
    {
        var spec = Plan.Spec;
        return new SweepRecord
        {
            SoftwareVersion = RunRecord.CurrentSoftwareVersion,
            StartedAt = startedAt,
            EndedAt = Options.WallClock.GetLocalNow(),
            Outcome = tally.Outcome,
            Fault = tally.Fault,
            Pattern = spec.Pattern.ToString().ToLowerInvariant(),
            CellImage = spec.Pattern == SweepPattern.Image ? spec.CellImageName : null,
            CellMm = spec.CellMm,
            SpacingMm = spec.SpacingMm,
            OriginXMm = spec.Origin.X,
            OriginYMm = spec.Origin.Y,
            Rows = spec.Rows.ToString(),
            Columns = spec.Columns?.ToString(),
            Simulated = Machine.Simulated,
            Notes = Options.Notes,
            SampleId = Options.SampleId,
            Labels = tally.Labels,
            Cells =
            [
                .. Plan.Cells.Select(c => new SweepCellRecord(
                    c.Row,
                    c.Column,
                    c.Parameters,
                    c.OriginXMm,
                    c.OriginYMm,
                    c.Job.Geometry.AchievedWidthMm,
                    c.Job.Geometry.AchievedHeightMm,
                    c.Job.Geometry.PitchUm,
                    c.Job.Spec.Passes,
                    tally.Runs.GetValueOrDefault(c))
                {
                    FocusZMicrosteps = c.FocusZMicrosteps,
                    ZReachedMicrosteps = tally.ReachedZ.TryGetValue(c, out var reached) ? reached : null,
                }),
            ],
        };
    }

    // A focus move that Abort can stop.
    private async Task<long> MoveFocusAsync(FocusAxis focus, long microsteps, CancellationToken cancellationToken)
    {
        lock (_lock)
        {
            if (_abortRequested)
            {
                throw new OperationCanceledException("the sweep was aborted");
            }

            _focusMoving = focus;
        }

        try
        {
            return await focus.MoveToAsync(microsteps, cancellationToken);
        }
        finally
        {
            lock (_lock)
            {
                _focusMoving = null;
            }
        }
    }

    private sealed class Relay(Action<EngraveProgress> report) : IProgress<EngraveProgress>
    {
        public void Report(EngraveProgress value) => report(value);
    }
}
