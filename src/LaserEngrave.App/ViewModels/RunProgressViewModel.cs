using CommunityToolkit.Mvvm.ComponentModel;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.App.ViewModels;

/// <summary>
/// The run bar's state: the run under way or the last one, its progress, time elapsed and left, the layer, where it
/// stopped, its error and the drawn laser. It holds no other view-model: <see cref="RunViewModel"/> tells it what
/// happens, and it answers with the figures the page and the API show.
/// </summary>
public sealed partial class RunProgressViewModel : ObservableObject
{
    private readonly TimeProvider _time;
    private readonly Func<MachineProfile> _profile;
    private EngraveJob? _running;
    private long _startedTicks;
    private double _estimatedSeconds;
    private double[] _passSeconds = [];

    /// <param name="profile">The machine profile now, to say where the stage stopped in mm.</param>
    public RunProgressViewModel(TimeProvider time, Func<MachineProfile> profile)
    {
        ArgumentNullException.ThrowIfNull(time);
        ArgumentNullException.ThrowIfNull(profile);
        _time = time;
        _profile = profile;
    }

    /// <summary>The run's state, as its session reports it (Idle before any run; Failed also for a run refused before it started).</summary>
    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(StateName))]
    public partial RunState State { get; internal set; }

    /// <summary>
    /// Where the stage drawing puts the laser while a run is under way (any kind of job): the motion in flight at its
    /// planned pace between the engine's reports (see <see cref="LaserPace"/>); null when no run is under way (the
    /// machine's own position then).
    /// </summary>
    [ObservableProperty]
    public partial (long X, long Y)? LaserMicrosteps { get; internal set; }

    /// <summary>The drawn laser with the instant on the machine's clock it stands for, in one value (the stage view tells the page both); null with <see cref="LaserMicrosteps"/>.</summary>
    public PacedLaser? PacedLaser { get; private set; }

    /// <summary>The latest progress of the run under way (or of the last one).</summary>
    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(LayerText), nameof(ProgressUnit))]
    public partial EngraveProgress? Progress { get; internal set; }

    /// <summary>The plan version the run executes, so the page draws the burned part over the right plan.</summary>
    [ObservableProperty]
    public partial int RunPlanVersion { get; internal set; }

    /// <summary>Why the last run failed or was refused, one line; null otherwise.</summary>
    [ObservableProperty]
    public partial string? Error { get; internal set; }

    /// <summary>One line for the user on a request that did nothing, e.g. a second Start during a run.</summary>
    [ObservableProperty]
    public partial string? Notice { get; internal set; }

    [ObservableProperty]
    public partial double ElapsedSecondsAtEnd { get; internal set; }

    /// <summary>Where the last run stopped (failed or aborted); kept, with the plan it ran, until a run completes or starts afresh.</summary>
    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(StoppedText))]
    public partial RunStopPoint? StoppedAt { get; internal set; }

    /// <summary>
    /// The state as docs/api.md names it: Idle, Running (preflight included), Paused (pausing included), Aborting,
    /// Completed, Aborted, Failed. <see cref="State"/> has the engine's finer state.
    /// </summary>
    public string StateName => State switch
    {
        RunState.Preflight => nameof(RunState.Running),
        RunState.Pausing => nameof(RunState.Paused),
        _ => State.ToString(),
    };

    /// <summary>
    /// Where the stopped run stopped, as the log's <c>Stopped at</c> says it: the rows done of the run bar's count and the
    /// stage in mm (<see cref="RunSummaryText.StagePlace"/>); null when no run stopped.
    /// </summary>
    public string? StoppedText => StoppedAt is not { } stop ? null
        : $"stopped after {Progress?.Run.RowsDone ?? 0} of {Progress?.Run.RowsTotal ?? 0} {ProgressUnit}s"
            + (stop is { XMicrosteps: { } x, YMicrosteps: { } y } ? $", {RunSummaryText.StagePlace(x, y, _profile())}" : string.Empty);

    public bool IsActive => State is RunState.Preflight or RunState.Running or RunState.Pausing or RunState.Paused or RunState.Aborting;

    /// <summary>What the run counts, as the command line and the log say it: strokes for a drawing (or a drawing's layer), else rows.</summary>
    public string ProgressUnit => _running?.UnitOf(Progress?.Layer ?? 0) ?? JobPart.RowUnit;

    /// <summary>The layers of the job under way (a job of layers); null for a single job or when nothing has run.</summary>
    public int? LayerCount => _running?.Layers is { Count: > 0 } layers ? layers.Count : null;

    /// <summary>The layer under way as "layer 2 of 3 “logo”"; null when the run is not one of layers.</summary>
    public string? LayerText => _running?.Layers is { Count: > 0 } layers && Progress is { } p && p.Layer >= 1 && p.Layer <= layers.Count
        ? $"layer {p.Layer} of {layers.Count} “{layers[p.Layer - 1].Layer.Name}”"
        : null;

    /// <summary>Whether a pause can be asked: the run is starting or running and no pause is pending.</summary>
    public bool CanPause => State is RunState.Preflight or RunState.Running && Progress?.PauseRequested != true;

    /// <summary>Whether a pause is pending or holds the run (the session's own flag: the engine pauses after the current move).</summary>
    public bool CanResume => State is not RunState.Aborting && IsActive && Progress?.PauseRequested == true;

    /// <summary>Fraction of all passes done, 0..1.</summary>
    public double Fraction => Progress is { MovesTotal: > 0 } p ? p.Fraction : State == RunState.Completed ? 1 : 0;

    public double ElapsedSeconds => IsActive ? _time.GetElapsedTime(_startedTicks).TotalSeconds : ElapsedSecondsAtEnd;

    /// <summary>Time left: the executor's estimate once moves are done, the plan's estimate before that.</summary>
    public double RemainingSeconds
    {
        get
        {
            if (!IsActive)
            {
                return 0;
            }

            // The executor's figure for this pass, plus the estimate of the passes still to come.
            if (Progress is { } p && p.MovesDone > 0)
            {
                return p.Run.Remaining.TotalSeconds + _passSeconds.Skip(p.Pass).Sum();
            }

            return Math.Max(0, _estimatedSeconds * (1 - Fraction));
        }
    }

    /// <summary>Draws the laser where the run's pace puts it (null: no laser drawn, the machine's own position again).</summary>
    internal void ShowLaser(PacedLaser? laser)
    {
        // The instant first: whoever is told the position has moved reads the instant that goes with it.
        PacedLaser = laser;
        LaserMicrosteps = laser is { } l ? (l.X, l.Y) : null;
    }

    /// <summary>A run of <paramref name="job"/> begins now, continuing a stopped one from <paramref name="resumeFrom"/> or <paramref name="resumeLayers"/> when given.</summary>
    internal void Began(EngraveJob job, RunStopPoint? resumeFrom, LayerResumePoint? resumeLayers)
    {
        _startedTicks = _time.GetTimestamp();
        _estimatedSeconds = job.EstimatedSeconds;
        _running = job;

        // Each pass's engraving with what goes before it, in run order: what is left once a pass is under way.
        _passSeconds = [.. job.PassSeconds(resumeFrom, resumeLayers)];
    }

    /// <summary>
    /// A report of the session under way: its progress, and its state while it runs (the start and the end are the
    /// owner's to set, the end once the log is in). True when it changed whether a pause is pending.
    /// </summary>
    internal bool Mirror(EngraveProgress progress)
    {
        var pauseChanged = Progress?.PauseRequested != progress.PauseRequested;
        Progress = progress;
        if (progress.State is not RunState.Idle && !RunStateMachine.IsEnd(progress.State))
        {
            State = progress.State;
        }

        return pauseChanged;
    }

    /// <summary>The run ended: a failure's reason stands in the bar.</summary>
    internal void Ended(EngraveResult result)
    {
        if (result.State == RunState.Failed)
        {
            // Which path confirmed the laser off is said only when it was not the usual OFF (docs/execution.md).
            Error = result.Record.Fault is { } fault
                ? fault.LaserOffBy is null or LaserOffPath.Off ? fault.Message : $"{fault.Message}; laser off: {RunSummaryText.LaserOff(fault)}"
                : "the run failed";
        }
    }

    /// <summary>The run's engine has stopped: the time it took stands.</summary>
    internal void Stopped() => ElapsedSecondsAtEnd = _time.GetElapsedTime(_startedTicks).TotalSeconds;

    /// <summary>
    /// The last run's bar, its percentage and its error, belong to the job it ran: once that job changed (another image,
    /// an edit, the layers changed), the bar is idle again. Where a stopped run stopped is kept.
    /// </summary>
    internal void JobChanged(int planVersion, bool layersChanged)
    {
        if (IsActive || (!layersChanged && RunPlanVersion == planVersion))
        {
            return;
        }

        Progress = null;
        Error = null;
        if (State is RunState.Completed or RunState.Aborted or RunState.Failed)
        {
            State = RunState.Idle;
        }
    }
}
