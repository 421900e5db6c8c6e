using CommunityToolkit.Mvvm.ComponentModel;
using CommunityToolkit.Mvvm.Input;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Machines.Runs;

namespace LaserEngrave.App.ViewModels;

/// <summary>The Preview view's run: start, pause, resume, abort (always allowed), and live progress.</summary>
/// <remarks>
/// The run is an <see cref="EngraveRun"/>, the use case the command line and the API run: this view-model only starts it,
/// forwards pause, resume and abort, and mirrors its state and progress, the latest value only (the page samples it at
/// its own pace, so a run of many short moves never floods it). Abort switches the laser off before the axes stop.
/// </remarks>
public sealed partial class RunViewModel : ObservableObject
{
    private readonly IRunService _runs;
    private readonly IJobSession _job;
    private readonly MachineViewModel _machine;
    private readonly LogViewModel _log;
    private readonly TimeProvider _time;
    private readonly LayersViewModel? _layers;
    private EngraveSession? _session;
    private CancellationTokenSource? _abort;
    private RunLaserDriver? _laser;

    /// <summary>How often the laser's drawn position is moved on between the engine's reports, on the app's clock.</summary>
    public static readonly TimeSpan PaceInterval = TimeSpan.FromMilliseconds(100);

    /// <param name="layers">The job of layers: while it has layers, Start runs them instead of the single job.</param>
    public RunViewModel(IRunService runs, IJobSession job, MachineViewModel machine, LogViewModel log, TimeProvider time, LayersViewModel? layers = null)
    {
        _runs = runs ?? throw new ArgumentNullException(nameof(runs));
        _job = job ?? throw new ArgumentNullException(nameof(job));
        _machine = machine ?? throw new ArgumentNullException(nameof(machine));
        _log = log ?? throw new ArgumentNullException(nameof(log));
        _time = time ?? throw new ArgumentNullException(nameof(time));
        _layers = layers;
        Bar = new RunProgressViewModel(time, () => machine.Profile);
        Continue = new RunContinueViewModel(job, machine, log, layers, Bar, RunAsync);

        // The bar's figures and Continue's are this view-model's too (the page and the API read them here): raised as ours.
        Bar.PropertyChanged += (_, e) =>
        {
            OnPropertyChanged(e);
            if (e.PropertyName is nameof(State) or nameof(StoppedAt) or nameof(RunPlanVersion))
            {
                RefreshCommands();
            }
        };
        Continue.PropertyChanged += (_, e) => OnPropertyChanged(e);
        Question.PropertyChanged += (_, e) =>
        {
            OnPropertyChanged(e.PropertyName == nameof(StartQuestionViewModel.Pending) ? nameof(PendingQuestion) : e.PropertyName);
            if (e.PropertyName == nameof(AskAboveMinutes))
            {
                OnPropertyChanged(nameof(StartQuestion));
            }
        };
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
            }
        };
        _machine.Activity.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(MachineActivity.Current))
            {
                RefreshCommands();
            }
        };
        _job.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(IJobSession.PlanVersion))
            {
                ClearStaleProgress();
            }

            RefreshCommands();
        };
        _machine.PropertyChanged += (_, _) => RefreshCommands();
    }

    /// <summary>The run bar's state.</summary>
    public RunProgressViewModel Bar { get; }

    /// <summary>Continue, of the stopped run or a logged one.</summary>
    public RunContinueViewModel Continue { get; }

    // The bar's and Continue's members, where the page, the API and the tests have always found them.
    public RunState State { get => Bar.State; private set => Bar.State = value; }

    public EngraveProgress? Progress { get => Bar.Progress; private set => Bar.Progress = value; }

    public int RunPlanVersion { get => Bar.RunPlanVersion; private set => Bar.RunPlanVersion = value; }

    public string? Error { get => Bar.Error; private set => Bar.Error = value; }

    public string? Notice { get => Bar.Notice; private set => Bar.Notice = value; }

    public RunStopPoint? StoppedAt { get => Bar.StoppedAt; private set => Bar.StoppedAt = value; }

    public (long X, long Y)? LaserMicrosteps => Bar.LaserMicrosteps;

    public PacedLaser? PacedLaser => Bar.PacedLaser;

    public bool IsActive => Bar.IsActive;

    public bool CanPause => Bar.CanPause;

    public bool CanResume => Bar.CanResume;

    public double Fraction => Bar.Fraction;

    public double RemainingSeconds => Bar.RemainingSeconds;

    public bool CanContinue => Continue.CanContinue;

    public string? ContinueUnavailableReason => Continue.ContinueUnavailableReason;

    public IAsyncRelayCommand ContinueCommand => Continue.ContinueCommand;

    /// <summary>What Start would run: the job of layers while there are layers, else the image or drawing; null when it does not plan.</summary>
    private EngraveJob? Planned => RunsLayers ? _layers!.Engraving : _job.Engraving;

    /// <summary>
    /// Whether <see cref="StartCommand"/> would run: nothing holds the machine (the interlock decides first), a planned job
    /// with something to burn inside the travel and no field the job rules refuse, a machine.
    /// </summary>
    public bool CanStart => !_machine.Activity.IsBusy && !IsActive
        && (RunsLayers ? _layers!.Error is null : _job.Errors.Count == 0)
        && Planned is { StartProblem: null }
        && _machine.Connection is not null
        && _machine.NoWatchdogUnaccepted is null;

    /// <summary>Whether Start runs the job of layers (the Layers view has some) rather than the single job.</summary>
    public bool RunsLayers => _layers is { IsActive: true };

    /// <summary>The long-run question's threshold at the first start: an hour.</summary>
    public const double DefaultAskAboveMinutes = StartQuestionViewModel.DefaultAskAboveMinutes;

    /// <summary>What Start asks before it runs, and the question waiting for its answer.</summary>
    public StartQuestionViewModel Question { get; } = new();

    /// <inheritdoc cref="StartQuestionViewModel.AskAboveMinutes"/>
    public double AskAboveMinutes { get => Question.AskAboveMinutes; set => Question.AskAboveMinutes = value; }

    /// <summary>What to ask before Start runs this job, with its numbers (<see cref="StartQuestionViewModel.For"/>); null when Start need not ask.</summary>
    public string? StartQuestion => Question.For(Planned?.EstimatedSeconds, Planned?.SmallestPixelUm, _job.Profile.SpotDiameterUm);

    /// <inheritdoc cref="StartQuestionViewModel.Pending"/>
    public string? PendingQuestion => Question.Pending;

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
            Question.Ask(question, AskedJob());
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
        if (Question.Answer(AskedJob(), StartQuestion) is { } changed)
        {
            Notice = changed;
            return Task.CompletedTask;
        }

        return StartNowAsync();
    }

    /// <summary>The answer "Cancel": nothing starts.</summary>
    [RelayCommand]
    private void CancelStart() => Question.Cancel();

    // The job a question is asked about: the plan's and the layers' versions, and which of them Start runs.
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

        if (NotReady() is { } problem)
        {
            // A run refused before it starts: the reason stands in the run bar.
            Error = problem;
            State = RunState.Failed;
            return;
        }

        await RunAsync(new RunOrder(Planned!, _job.ToSettings()));
    }

    /// <summary>
    /// Why Start would be refused now, one line (what holds the machine, no job, not connected, the gate's watchdog
    /// unaccepted, then the run's own checks: a job that cannot run, a log folder that takes no file, marks burned
    /// already); null when it would start. Reads the log's folder: for a request to start, not for a button's state.
    /// </summary>
    public string? StartRefusal() => _machine.Activity.BusyMessage ?? NotReady() ?? NewRun(new RunOrder(Planned!, _job.ToSettings())).Check()?.Message;

    // What the run bar's Start needs besides the run's own checks: a job that plans and a machine to run it on.
    private string? NotReady()
    {
        var job = Planned;
        var unplanned = RunsLayers
            ? _layers!.Error ?? (job is null ? "the layers do not plan" : null)
            : job is null ? "no job planned: open an image and give it a usable size first" : null;
        return unplanned ?? (job is not null && EngraveRun.Unrunnable(job) is { } unrunnable ? unrunnable : null)
            ?? (_machine.Connection is null ? "not connected: connect to the simulator or the machine first" : null)
            ?? _machine.NoWatchdogUnaccepted;
    }

    /// <summary>The run use case for the order with the log panel's fields, this app's log and clock.</summary>
    private EngraveRun NewRun(RunOrder order) => new(
        order.Request(_log.Notes, _log.SampleId, _log.LastRun?.Path, _layers?.UnchangedJobFile, _machine.AcceptNoWatchdog, _time),
        new RunLog(_log.Writer, _log.CheckWritable));

    [RelayCommand(CanExecute = nameof(CanPause))]
    private void Pause() => Control(CanPause, session => session.Pause());

    [RelayCommand(CanExecute = nameof(CanResume))]
    private void Resume() => Control(CanResume, session => session.Resume());

    /// <summary>Aborts the run; always allowed, harmless when nothing runs.</summary>
    [RelayCommand]
    private void Abort() => Control(IsActive, session =>
    {
        session.Abort();
        _abort?.Cancel();
    });

    // Asks the session under way, when there is one and it may be asked, and shows at once what it says.
    private void Control(bool may, Action<EngraveSession> ask)
    {
        if (_session is { } session && may)
        {
            ask(session);
            Mirror(session, session.Progress);
        }
    }

    /// <summary>Takes the session's state and progress while it runs; the start and the end are this view-model's to set (the end once the log is in).</summary>
    private void Mirror(EngraveSession session, EngraveProgress progress)
    {
        // Only the session under way: a report of an ended one (late on its thread) changes nothing.
        if (ReferenceEquals(session, _session) && Bar.Mirror(progress))
        {
            RefreshCommands();
        }
    }

    /// <summary>Runs the order on the connected machine: the run's checks, its session mirrored here, then its end in the run bar and the log panel.</summary>
    private async Task RunAsync(RunOrder order)
    {
        var connection = _machine.Connection!;
        var run = NewRun(order);
        if (!_machine.Activity.TryBegin(MachineOperation.Run, out var lease, out var refusal))
        {
            Error = refusal;
            return;
        }

        using var held = lease;
        if (run.Check() is { } refused)
        {
            Error = refused.Message;
            State = RunState.Failed;
            return;
        }

        var request = run.Request;
        var job = request.Job;
        Bar.Began(job, request.ResumeFrom, request.ResumeLayers);
        // On real ports every byte in and out is recorded beside the log, as the command line's runs are (`laserengrave replay`).
        var running = run.Open(connection.Engraving(), connection.StartRecording(_log.Folder));
        StoppedAt = null;
        RunPlanVersion = _job.PlanVersion;
        _session = running;
        Progress = running.Progress;
        State = RunState.Preflight;
        EngraveResult result;

        // Abort (or the app's exit) cancels this; a second Start or Continue never does.
        using var abort = CancellationTokenSource.CreateLinkedTokenSource(lease.CancellationToken);
        _abort = abort;

        // Every kind of job counts its moves one for one with the engine: its laser is drawn at their pace, on the machine's
        // clock (the engine's), which the simulator's virtual time can hold behind the app's.
        _laser = new RunLaserDriver(new LaserPace(job, connection.TimeProvider, running.StrokePositionAt), _time, PaceInterval, () => Progress is { } p ? p.State == RunState.Running : null, Bar.ShowLaser);
        try
        {
            result = await _runs.RunAsync(running, new LatestProgress(this, running), abort.Token);
        }
        finally
        {
            _laser.Dispose();
            _laser = null;
            _abort = null;
            Bar.Stopped();
        }

        Ended(run, order.Settings, result);
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
        State = result.State;
    }

    /// <summary>A run's end in the run bar (its error, where it stopped), in Continue and in the log panel.</summary>
    private void Ended(EngraveRun run, JobSettings settings, EngraveResult result)
    {
        Bar.Ended(result);
        StoppedAt = Continue.Stopped.Ended(run.Request.Job, settings, result.Record, _layers?.Layers);
        _log.Recorded(result.Record, result.Files, result.LogError);
    }

    private void RefreshCommands()
    {
        StartCommand.NotifyCanExecuteChanged();
        ConfirmStartCommand.NotifyCanExecuteChanged();
        PauseCommand.NotifyCanExecuteChanged();
        ResumeCommand.NotifyCanExecuteChanged();
    }

    /// <summary>A new plan makes the last run's figures meaningless for it ("100 %, row 33 of 33" on a job never run).</summary>
    private void ClearStaleProgress(bool layersChanged = false) => Bar.JobChanged(_job.PlanVersion, layersChanged);

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
            owner._laser?.Report(value.Layer, value.Pass, value.MovesDone, value.Run.XMicrosteps, value.Run.YMicrosteps);
        }
    }
}
