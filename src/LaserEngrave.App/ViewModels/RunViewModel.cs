using System.Globalization;
using System.Text.Json;
using CommunityToolkit.Mvvm.ComponentModel;
using CommunityToolkit.Mvvm.Input;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.App.ViewModels;

/// <summary>The Preview view's run: start, pause, resume, abort (always allowed), and live progress.</summary>
/// <remarks>
/// The run is an <see cref="EngraveSession"/>, the same the command line runs: this view-model only starts it, forwards
/// pause, resume and abort, and mirrors its state and progress. Progress is stored as the latest value only: the page
/// samples it at its own pace, so a run of many short moves never floods it. Abort switches the laser off before the
/// axes stop.
/// </remarks>
public sealed partial class RunViewModel : ObservableObject
{
    private readonly IRunService _runs;
    private readonly JobViewModel _job;
    private readonly MachineViewModel _machine;
    private readonly LogViewModel _log;
    private readonly TimeProvider _time;
    private readonly LayersViewModel? _layers;
    private EngraveSession? _session;
    private EngraveJob? _running;
    private CancellationTokenSource? _abort;
    private StoppedRun? _stopped;
    private ((int Job, int Layers) PlanVersion, string? Reason) _continueCheck = ((-1, -1), null);
    private long _startedTicks;
    private double _estimatedSeconds;
    private double[] _passSeconds = [];
    private LaserPace? _pace;

    // The pace's timer ticks on the pool: a tick never sets the drawn laser again once the run has cleared it.
    private readonly Lock _paceLock = new();

    /// <summary>How often the laser's drawn position is moved on between the engine's reports, on the app's clock.</summary>
    public static readonly TimeSpan PaceInterval = TimeSpan.FromMilliseconds(100);

    /// <param name="layers">The job of layers: while it has layers, Start runs them instead of the single job.</param>
    public RunViewModel(IRunService runs, JobViewModel job, MachineViewModel machine, LogViewModel log, TimeProvider time, LayersViewModel? layers = null)
    {
        ArgumentNullException.ThrowIfNull(runs);
        ArgumentNullException.ThrowIfNull(job);
        ArgumentNullException.ThrowIfNull(machine);
        ArgumentNullException.ThrowIfNull(log);
        ArgumentNullException.ThrowIfNull(time);
        _runs = runs;
        _job = job;
        _machine = machine;
        _log = log;
        _time = time;
        _layers = layers;
        _layers?.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName is nameof(LayersViewModel.Job) or nameof(LayersViewModel.Layers))
            {
                if (e.PropertyName == nameof(LayersViewModel.Layers))
                {
                    ClearStaleProgress(layersChanged: true);
                }

                RefreshCommands();
                OnPropertyChanged(nameof(RunsLayers));
                OnPropertyChanged(nameof(CanContinue));
                OnPropertyChanged(nameof(ContinueUnavailableReason));
            }
        };
        _machine.Activity.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(MachineActivity.Current))
            {
                RefreshCommands();
                OnPropertyChanged(nameof(CanContinue));
                OnPropertyChanged(nameof(ContinueUnavailableReason));
            }
        };
        _job.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(JobViewModel.PlanVersion))
            {
                ClearStaleProgress();
                OnPropertyChanged(nameof(CanContinue));
                OnPropertyChanged(nameof(ContinueUnavailableReason));
            }

            RefreshCommands();
        };
        _machine.PropertyChanged += (_, _) => RefreshCommands();
        PropertyChanged += (_, e) =>
        {
            if (e.PropertyName is nameof(State) or nameof(StoppedAt) or nameof(RunPlanVersion))
            {
                RefreshCommands();
            }
        };
    }

    /// <summary>The run's state, as its session reports it (Idle before any run; Failed also for a run refused before it started).</summary>
    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(StateName))]
    public partial RunState State { get; private set; }

    /// <summary>
    /// Where the stage drawing puts the laser while a run is under way (any kind of job): the motion in flight at its
    /// planned pace between the engine's reports (see <see cref="LaserPace"/>); null when no run is under way (the
    /// machine's own position then).
    /// </summary>
    [ObservableProperty]
    public partial (long X, long Y)? LaserMicrosteps { get; private set; }

    /// <summary>The drawn laser with the instant on the machine's clock it stands for, in one value (the stage view tells the page both); null with <see cref="LaserMicrosteps"/>.</summary>
    public PacedLaser? PacedLaser { get; private set; }

    /// <summary>The latest progress of the run under way (or of the last one).</summary>
    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(LayerText), nameof(ProgressUnit))]
    public partial EngraveProgress? Progress { get; private set; }

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

    /// <summary>The plan version the run executes, so the page draws the burned part over the right plan.</summary>
    [ObservableProperty]
    public partial int RunPlanVersion { get; private set; }

    [ObservableProperty]
    public partial string? Error { get; private set; }

    [ObservableProperty]
    public partial double ElapsedSecondsAtEnd { get; private set; }

    /// <summary>Where the last run stopped (failed or aborted); kept, with the plan it ran, until a run completes or starts afresh.</summary>
    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(CanContinue), nameof(ContinueUnavailableReason), nameof(StoppedText))]
    [NotifyCanExecuteChangedFor(nameof(ContinueCommand))]
    public partial RunStopPoint? StoppedAt { get; private set; }

    /// <summary>
    /// Where the stopped run stopped, as the log's <c>Stopped at</c> says it: the rows done of the run bar's count and the
    /// stage in mm (<see cref="RunSummaryText.StagePlace"/>); null when no run stopped.
    /// </summary>
    public string? StoppedText => StoppedAt is not { } stop ? null
        : $"stopped after {Progress?.Run.RowsDone ?? 0} of {Progress?.Run.RowsTotal ?? 0} {ProgressUnit}s"
            + (stop is { XMicrosteps: { } x, YMicrosteps: { } y } ? $", {RunSummaryText.StagePlace(x, y, _machine.Profile)}" : string.Empty);

    /// <summary>Whether <see cref="ContinueCommand"/> can pick the stopped run up: the job as it stopped, nothing under way.</summary>
    public bool CanContinue => StoppedAt is not null && ContinueUnavailableReason is null;

    /// <summary>
    /// Why a stopped run cannot be continued now, one line (e.g. the job changed, naming what); null when it can, or when
    /// no run stopped. Setting the job back as it was offers Continue again.
    /// </summary>
    public string? ContinueUnavailableReason => StoppedAt is null ? null : WhyNotContinue();

    public bool IsActive => State is RunState.Preflight or RunState.Running or RunState.Pausing or RunState.Paused or RunState.Aborting;

    /// <summary>
    /// Whether <see cref="StartCommand"/> would run: nothing holds the machine (the interlock decides first), a planned job
    /// with something to burn inside the travel and no field the job rules refuse, a machine.
    /// </summary>
    public bool CanStart => !_machine.Activity.IsBusy && !IsActive
        && (RunsLayers ? _layers!.Error is null : _job.Errors.Count == 0)
        && Planned is { StartProblem: null }
        && _machine.Connection is not null
        && _machine.NoWatchdogUnaccepted is null;

    /// <summary>What Start would run: the job of layers while there are layers, else the image or drawing; null when it does not plan.</summary>
    private EngraveJob? Planned => RunsLayers ? _layers!.Engraving : _job.Engraving;

    /// <summary>Whether Start runs the job of layers (the Layers view has some) rather than the single job.</summary>
    public bool RunsLayers => _layers is { IsActive: true };

    /// <summary>What the run counts, as the command line and the log say it: strokes for a drawing (or a drawing's layer), else rows.</summary>
    public string ProgressUnit => _running?.UnitOf(Progress?.Layer ?? 0) ?? PreparedLayer.RowUnit;

    /// <summary>The layer under way as "layer 2 of 3 “logo”"; null when the run is not one of layers.</summary>
    /// <summary>The layers of the job under way (a job of layers); null for a single job or when nothing has run.</summary>
    public int? LayerCount => _running?.Layers is { Count: > 0 } layers ? layers.Count : null;

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

    /// <summary>The long-run question's threshold at the first start: an hour.</summary>
    public const double DefaultAskAboveMinutes = 60;

    /// <summary>
    /// A run longer than this, minutes (the estimate, all passes), asks before it starts, in the page and through the API;
    /// the user's setting (<see cref="MainViewModel.SetAskAboveMinutes"/>), an hour until set.
    /// </summary>
    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(StartQuestion))]
    public partial double AskAboveMinutes { get; set; } = DefaultAskAboveMinutes;

    /// <summary>
    /// What to ask before Start runs this job, with its numbers: a run longer than <see cref="AskAboveMinutes"/>, or pixels less than half the laser
    /// spot (each burns several times wider than it is); null when Start need not ask.
    /// </summary>
    public string? StartQuestion
    {
        get
        {
            var estimate = Planned?.EstimatedSeconds;
            var spot = _job.Profile.SpotDiameterUm;
            var pitch = Planned?.SmallestPixelUm;
            var reasons = new List<string>();
            if (estimate > AskAboveMinutes * 60)
            {
                reasons.Add($"it takes about {Components.Format.Duration(estimate.Value)}");
            }

            if (pitch < spot / 2)
            {
                reasons.Add(string.Create(CultureInfo.InvariantCulture, $"its pixels of {pitch:0.###} µm are much smaller than the {spot:0.#} µm laser spot, so each burns about {spot / pitch:0} times wider than it is"));
            }

            return reasons.Count == 0 ? null : $"Start anyway? {char.ToUpperInvariant(reasons[0][0])}{string.Join("; and ", reasons)[1..]}.";
        }
    }

    /// <summary>The question Start asked (<see cref="StartQuestion"/>), waiting for Start anyway or Cancel; null when none waits.</summary>
    [ObservableProperty]
    public partial string? PendingQuestion { get; private set; }

    /// <summary>Runs the planned job on the connected machine; <see cref="AbortCommand"/> stops it.</summary>
    /// <remarks>
    /// A second Start while a run is under way is ignored (never taken as an abort); <see cref="Notice"/> says so. A job
    /// of over an hour, or of pixels much smaller than the spot, asks first (<see cref="PendingQuestion"/>).
    /// </remarks>
    [RelayCommand(CanExecute = nameof(CanStart))]
    private async Task StartAsync()
    {
        if (!IsActive && StartQuestion is { } question)
        {
            Notice = null;
            _askedAbout = AskedJob();
            PendingQuestion = question;
            return;
        }

        await StartNowAsync();
    }

    /// <summary>
    /// Starts the job Start asked about: the answer "Start anyway". A job changed while the question showed is not
    /// started: the question is asked again for the job as it is now, or, when that one need not ask, nothing starts
    /// and <see cref="Notice"/> says so.
    /// </summary>
    [RelayCommand(CanExecute = nameof(CanStart))]
    private Task ConfirmStartAsync()
    {
        if (PendingQuestion is not null && _askedAbout != AskedJob())
        {
            var question = StartQuestion;
            PendingQuestion = question;
            _askedAbout = AskedJob();
            Notice = question is null
                ? "the job changed while Start was asking: nothing started; press Start to run the job as it is now"
                : "the job changed while Start was asking: the question is asked again for the job as it is now";
            return Task.CompletedTask;
        }

        PendingQuestion = null;
        return StartNowAsync();
    }

    /// <summary>The answer "Cancel": nothing starts.</summary>
    [RelayCommand]
    private void CancelStart() => PendingQuestion = null;

    // The job the pending question was asked about: the plan's and the layers' versions, and which of them Start runs.
    private (int Job, int Layers, bool RunsLayers) _askedAbout;

    private (int Job, int Layers, bool RunsLayers) AskedJob() => (_job.PlanVersion, _layers?.PlanVersion ?? 0, RunsLayers);

    /// <summary>Starts without asking (the API's start with "confirm": true, or the answer to the question).</summary>
    internal async Task StartNowAsync()
    {
        if (IsActive)
        {
            Notice = "a run is already under way: this Start was ignored";
            return;
        }

        Error = null;
        Notice = null;
        if (_machine.Activity.BusyMessage is { } busy)
        {
            Error = busy;
            return;
        }

        var connection = _machine.Connection;
        var job = Planned;
        var unplanned = RunsLayers
            ? _layers!.Error ?? (job is null ? "the layers do not plan" : null)
            : job is null ? "no job planned: open an image and give it a usable size first" : null;
        if (!Refused(unplanned ?? job!.StartProblem ?? (connection is null ? "not connected: connect to the simulator or the machine first" : null) ?? _machine.NoWatchdogUnaccepted))
        {
            await RunAsync(job!, _job.ToSettings(), connection!);
        }

        // A run refused before it starts: the reason stands in the run bar.
        bool Refused(string? problem)
        {
            if (problem is null)
            {
                return false;
            }

            Error = problem;
            State = RunState.Failed;
            return true;
        }
    }

    /// <summary>
    /// Continues the run that stopped (a fault or an abort) from its first burn run not completed, laser off on the way
    /// there, so the sample ends with no gap and nothing burned twice. Only with the plan it stopped on, while the job
    /// is as it was then; <see cref="ContinueUnavailableReason"/> says why not otherwise.
    /// </summary>
    [RelayCommand(CanExecute = nameof(CanContinue))]
    private async Task ContinueAsync()
    {
        if (IsActive)
        {
            Notice = "a run is already under way: this Continue was ignored";
            return;
        }

        Error = null;
        Notice = null;
        var stopped = _stopped;
        var connection = _machine.Connection;
        var problem = StoppedAt is null || stopped is null ? "no stopped run to continue: the last run completed, or none ran"
            : WhyNotContinue();
        if (problem is not null)
        {
            Error = problem;
            return;
        }

        await RunAsync(stopped!.Job, stopped.Settings, connection!, stopped.Job.Layers is null ? stopped.StopPoint : null, stopped.LayerResume);
    }

    /// <summary>
    /// Why the logged run at <paramref name="path"/> cannot be continued from the run history now, one line; null when it
    /// can (a run that stopped with a stop point, made with the app's machine profile, a machine connected and free).
    /// </summary>
    public string? WhyNotContinueLogged(string path)
    {
        if (_log.Find(path)?.Record is not { } record)
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
        if (_log.History.FirstOrDefault(e => e.Record is { Resumed: true } later && later.RepeatOf == path) is { Record: { } continued } by)
        {
            return $"it was continued already ({Path.GetFileName(by.Path)}, {continued.Outcome.ToString().ToLowerInvariant()}){(continued.Outcome == RunOutcome.Completed ? string.Empty : ": continue that run instead")}";
        }

        if (record.Profile != _job.Profile)
        {
            return $"it ran with the machine profile \"{record.Profile.Name}\", the app plans with \"{_job.Profile.Name}\": continue it with laserengrave engrave --from-log LOG --resume";
        }

        if (IsActive)
        {
            return "a run is already under way";
        }

        return _machine.Activity.BusyMessage ?? (_machine.Connection is null ? "not connected: connect to the machine the run stopped on first" : null);
    }

    /// <summary>
    /// Continues a logged run that stopped (a fault or an abort) from the run history, as
    /// <c>laserengrave engrave --from-log LOG --resume</c> does: its image and values are put back (as Repeat does, the
    /// image checked against its SHA-256), planned again, and run from the log's stop point by the same path as
    /// <see cref="ContinueCommand"/>; the new log says it resumed that one. Refused with one line when
    /// <see cref="WhyNotContinueLogged"/> says why, or when the job planned now is not the logged run's.
    /// </summary>
    [RelayCommand]
    private async Task ContinueLoggedAsync(string path)
    {
        Error = null;
        Notice = null;
        if (WhyNotContinueLogged(path) is { } why)
        {
            Error = $"{Path.GetFileName(path)} cannot be continued: {why}";
            return;
        }

        var record = _log.Find(path)!.Record!;
        _log.LoadCommand.Execute(path);
        if (_log.Error is { } loadError)
        {
            Error = loadError;
            return;
        }

        // A drawing's stop point counts strokes, an image's rows: only a job of the logged kind can go on from it.
        var target = _job.Engraving is { } planned && planned is DrawingJob == record.Drawing is not null ? planned : null;
        var counts = target?.Planned ?? (-1, -1L);

        // The stop point counts the logged plan's moves: only the same plan, made again, can go on from it.
        if (target is null || counts != (record.RowsTotal, record.RunsTotal))
        {
            Error = $"{Path.GetFileName(path)} cannot be continued: the job planned from its log is not the one that ran ({(target is null ? "it does not plan" : $"{counts.Units} {record.RowsCounted} and {counts.Runs} runs, not {record.RowsTotal} and {record.RunsTotal}")}); Repeat runs it again";
            return;
        }

        // An older log's stop point may count an older planner's moves: where it stands in this plan (docs/run-log.md, "Older logs").
        var stop = target is RasterJob raster ? RunReplay.StopPointInPlan(record, () => raster.Prepared.Plan) : record.StoppedAt;
        await RunAsync(target, _job.ToSettings(), _machine.Connection!, stop, continuedFrom: path);
    }

    /// <summary>One line for the user on a request that did nothing, e.g. a second Start during a run.</summary>
    [ObservableProperty]
    public partial string? Notice { get; private set; }

    private string? WhyNotContinue()
    {
        if (_machine.Activity.BusyMessage is { } busy)
        {
            return busy;
        }

        if (_machine.Connection is null)
        {
            return "not connected: connect to the machine the run stopped on first";
        }

        var planVersion = (_job.PlanVersion, _layers?.PlanVersion ?? 0);
        var check = _continueCheck;
        if (check.PlanVersion != planVersion)
        {
            check = _continueCheck = (planVersion, _stopped is { } stopped ? JobDifference(stopped) : "no stopped run to continue");
        }

        return check.Reason;
    }

    /// <summary>What about the job differs from the one the run stopped on, as one line; null when nothing does.</summary>
    private string? JobDifference(StoppedRun stopped)
    {
        if (stopped.Job.Layers is not null)
        {
            return RunsLayers && _layers!.Layers.SequenceEqual(stopped.Layers ?? [])
                ? null
                : "the layers changed since the run stopped: continuing would not match what is burned; set them back to continue, or start again";
        }

        if (RunsLayers)
        {
            return "Start runs the layers now: clear them to continue the stopped job";
        }

        var now = JsonSerializer.SerializeToElement(_job.ToSettings(), JsonSerializerOptions.Web);
        var then = JsonSerializer.SerializeToElement(stopped.Settings, JsonSerializerOptions.Web);
        var changed = then.EnumerateObject()
            .Where(p => !now.TryGetProperty(p.Name, out var value) || value.GetRawText() != p.Value.GetRawText())
            .Select(p => p.Name)
            .Where(name => name != "passes")
            .Select(JobSettings.FieldLabel)
            .ToList();
        if (changed.Count == 0 && stopped.Job.Mask is { } burned && (_job.Mask is not { } mask || !mask.ContentEquals(burned)))
        {
            changed.Add("image");
        }

        return changed.Count == 0 ? null
            : $"the job changed since the run stopped ({string.Join(", ", changed)}): continuing would not match what is burned; set it back to continue, or start again";
    }

    [RelayCommand(CanExecute = nameof(CanPause))]
    private void Pause()
    {
        if (_session is { } session && CanPause)
        {
            session.Pause();
            Mirror(session);
        }
    }

    [RelayCommand(CanExecute = nameof(CanResume))]
    private void Resume()
    {
        if (_session is { } session && CanResume)
        {
            session.Resume();
            Mirror(session);
        }
    }

    /// <summary>Aborts the run; always allowed, harmless when nothing runs.</summary>
    [RelayCommand]
    private void Abort()
    {
        if (IsActive && _session is { } session)
        {
            session.Abort();
            _abort?.Cancel();
            Mirror(session);
        }
    }

    /// <summary>Takes the session's state and progress while it runs; the start and the end are this view-model's to set (the end once the log is in).</summary>
    private void Mirror(EngraveSession session) => Mirror(session, session.Progress);

    private void Mirror(EngraveSession session, EngraveProgress progress)
    {
        if (!ReferenceEquals(session, _session))
        {
            return;
        }

        var pauseChanged = Progress?.PauseRequested != progress.PauseRequested;
        Progress = progress;
        if (progress.State is not RunState.Idle && !RunStateMachine.IsEnd(progress.State))
        {
            State = progress.State;
        }

        if (pauseChanged)
        {
            RefreshCommands();
        }
    }

    /// <param name="job">What runs: an image job, a drawing or a job of layers.</param>
    /// <param name="resumeFrom">Continue a stopped image job or drawing from here (its stopped pass only).</param>
    /// <param name="resumeLayers">Continue a stopped job of layers from here (its layer and pass, then the rest).</param>
    /// <param name="continuedFrom">The log of the run this one continues (the last run's when none is given).</param>
    private async Task RunAsync(EngraveJob job, JobSettings settings, IMachineConnection connection, RunStopPoint? resumeFrom = null, LayerResumePoint? resumeLayers = null, string? continuedFrom = null)
    {
        if (!_machine.Activity.TryBegin(MachineOperation.Run, out var lease, out var refusal))
        {
            Error = refusal;
            return;
        }

        using var held = lease;
        try
        {
            // A run must not start without a place for its log (a read-only or full disk is found now, not after the burn).
            _log.CheckWritable();
        }
        catch (RunLogException ex)
        {
            Error = ex.Message;
            State = RunState.Failed;
            return;
        }

        try
        {
            // Marks whose numbers a completed run burned already are not burned again (two samples, one number); a continue is.
            if (resumeLayers is null && job.Layers is not null && _layers?.UnchangedJobFile is { } marked
                && Core.Marks.MarkManifest.BurnedAlready(marked) is { } burned)
            {
                Error = burned;
                State = RunState.Failed;
                return;
            }
        }
        catch (Core.Marks.MarkException ex)
        {
            Error = ex.Message;
            State = RunState.Failed;
            return;
        }

        continuedFrom = resumeFrom is null && resumeLayers is null ? null : continuedFrom ?? _log.LastRun?.Path;
        var layered = job.Layers is not null;
        _startedTicks = _time.GetTimestamp();
        _estimatedSeconds = job.EstimatedSeconds;
        _running = job;

        // Each pass's engraving with what goes before it, in run order: what is left once a pass is under way.
        _passSeconds = [.. job.PassSeconds(resumeFrom, resumeLayers)];
        var machine = new EngraveMachine(connection.Stage, connection.Gate, connection.TimeProvider, connection.Description, connection.Description)
        {
            Simulated = connection.IsSimulated,
            Inspector = connection.IsSimulated ? connection.Inspector : null,
        };
        var running = new EngraveSession(machine, job, new EngraveSessionOptions
        {
            Notes = _log.Notes,
            SampleId = _log.SampleId,
            RepeatOf = string.IsNullOrEmpty(continuedFrom) ? null : continuedFrom,
            ResumeFrom = resumeFrom,
            ResumeLayers = resumeLayers,
            JobFile = layered ? _layers?.UnchangedJobFile : null,
            Log = _log.Writer,
            WallClock = _time,
            AcceptNoWatchdog = _machine.AcceptNoWatchdog,

            // On real ports every byte in and out is recorded beside the log, as the command line's runs are (`laserengrave replay`).
            Recorder = connection.StartRecording(_log.Folder),
        });
        StoppedAt = null;
        RunPlanVersion = _job.PlanVersion;
        _session = running;
        Progress = running.Progress;
        State = RunState.Preflight;
        EngraveResult result;

        // Abort (or the app's exit) cancels this; a second Start or Continue never does.
        using var abort = CancellationTokenSource.CreateLinkedTokenSource(lease.CancellationToken);
        _abort = abort;

        // Every kind of job counts its moves (plan moves, dots, strokes) one for one with the engine: its laser is drawn at
        // their pace, on the machine's clock (the engine's), which the simulator's virtual time can hold behind the app's.
        var pace = new LaserPace(job, connection.TimeProvider, running.StrokePositionAt);
        _pace = pace;
        var paceTimer = _time.CreateTimer(_ => MoveLaser(), null, PaceInterval, PaceInterval);
        try
        {
            result = await _runs.RunAsync(running, new LatestProgress(this, running), abort.Token);
        }
        finally
        {
            paceTimer.Dispose();
            lock (_paceLock)
            {
                _pace = null;
                PacedLaser = null;
                LaserMicrosteps = null;
            }

            _abort = null;
            ElapsedSecondsAtEnd = _time.GetElapsedTime(_startedTicks).TotalSeconds;
        }

        var record = result.Record;
        var final = result.State;
        if (final == RunState.Failed)
        {
            // Which path confirmed the laser off is said only when it was not the usual OFF (docs/execution.md).
            Error = record.Fault is { } fault
                ? fault.LaserOffBy is null or LaserOffPath.Off ? fault.Message : $"{fault.Message}; laser off: {RunSummaryText.LaserOff(fault)}"
                : "the run failed";
        }

        var stopPoint = record.Outcome is RunOutcome.Failed or RunOutcome.Aborted ? record.StoppedAt : null;
        var layerResume = layered ? LayerResume(record) : null;
        if (layered && layerResume is null)
        {
            stopPoint = null;
        }

        _stopped = stopPoint is null ? null : new StoppedRun(job, settings, stopPoint, layerResume, layered ? _layers?.Layers : null);
        _continueCheck = ((-1, -1), null);
        StoppedAt = stopPoint;
        _log.Recorded(record, result.Files, result.LogError);
        try
        {
            // The whole state, not only the positions: the run's preflight homed the stage, and the view must say so.
            await _machine.RefreshStateAsync(CancellationToken.None);
        }
        catch (Exception ex) when (ex is DeviceException or InvalidOperationException or ObjectDisposedException or TimeoutException or IOException)
        {
            _machine.Error = ex.Message;
            _machine.StateNotKnown();
        }

        // The run counts as ended only once its log is written, so whoever waits for the end finds the log.
        _session = null;
        State = final;
    }

    /// <summary>Moves the drawn laser on along the move in flight; it stands where the engine last put it unless the run is moving.</summary>
    private void MoveLaser()
    {
        lock (_paceLock)
        {
            if (_pace is { } pace && Progress is { } progress)
            {
                var now = pace.Now(progress.State == RunState.Running, out var atSeconds);
                PacedLaser = now is { } p ? new PacedLaser(p.X, p.Y, atSeconds) : null;
                LaserMicrosteps = now;
            }
        }
    }

    private void RefreshCommands()
    {
        StartCommand.NotifyCanExecuteChanged();
        ConfirmStartCommand.NotifyCanExecuteChanged();
        ContinueCommand.NotifyCanExecuteChanged();
        PauseCommand.NotifyCanExecuteChanged();
        ResumeCommand.NotifyCanExecuteChanged();
    }

    /// <summary>A new plan makes the last run's figures meaningless for it ("100 %, row 33 of 33" on a job never run).</summary>
    /// <summary>
    /// The last run's bar, its percentage and its error, belong to the job it ran: once that job changed (another image,
    /// an edit, the layers changed), the bar is idle again. Where a stopped run stopped is kept (Continue says whether the
    /// job still is the one that stopped).
    /// </summary>
    private void ClearStaleProgress(bool layersChanged = false)
    {
        if (IsActive || (!layersChanged && RunPlanVersion == _job.PlanVersion))
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

    /// <summary>Where a stopped run of layers goes on, as the command line's <c>--resume</c> finds it in the log; null when nothing is left.</summary>
    private static LayerResumePoint? LayerResume(RunRecord record)
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

    /// <summary>
    /// A run that stopped before its end: what it ran, the job's values then, where it stopped, and for a job of layers
    /// its layers then and where it goes on.
    /// </summary>
    private sealed record StoppedRun(EngraveJob Job, JobSettings Settings, RunStopPoint StopPoint, LayerResumePoint? LayerResume, IReadOnlyList<JobLayer>? Layers);

    /// <summary>Keeps only the newest report: assigning a reference is all a serial reply costs the UI.</summary>
    private sealed class LatestProgress(RunViewModel owner, EngraveSession session) : IProgress<EngraveProgress>
    {
        public void Report(EngraveProgress value)
        {
            owner.Mirror(session, value);
            if (value.State is RunState.Running && (owner._machine.XHomed is not true || owner._machine.YHomed is not true))
            {
                owner._machine.PreflightHomed();
            }

            owner._machine.XMicrosteps = value.Run.XMicrosteps;
            owner._machine.YMicrosteps = value.Run.YMicrosteps;

            // The panel's and the API's laser come from the engine's report during a run, not from the gate read before it.
            var parts = session.Engraving.Parts;
            owner._machine.RunLaser(value.Run.LaserOn, parts[Math.Clamp(value.Layer - 1, 0, parts.Count - 1)].Spec.Process.LaserFrequencyWholeHz);
            if (owner._pace is { } pace)
            {
                pace.Report(value.Layer, value.Pass, value.MovesDone, value.Run.XMicrosteps, value.Run.YMicrosteps);
                owner.MoveLaser();
            }
        }
    }
}
