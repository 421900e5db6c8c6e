using CommunityToolkit.Mvvm.ComponentModel;
using CommunityToolkit.Mvvm.Input;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.App.ViewModels;

/// <summary>What a run asks of <see cref="RunViewModel"/>: the job, its values then, and where a continued run goes on from.</summary>
/// <param name="ContinuedFrom">The log of the run this one continues (the last run's when none is given and it resumes).</param>
internal sealed record RunOrder(EngraveJob Job, JobSettings Settings, RunStopPoint? ResumeFrom = null, LayerResumePoint? ResumeLayers = null, string? ContinuedFrom = null)
{
    /// <summary>The run use case's request for this order, with the log panel's notes and sample ID.</summary>
    /// <param name="lastRun">The last run's log: the one a resumed run continues when the order names none.</param>
    /// <param name="jobFile">The job file of the layers, unchanged since it was opened; logged (and its marks checked) for a job of layers only.</param>
    public Machines.Runs.RunRequest Request(string? notes, string? sampleId, string? lastRun, string? jobFile, bool acceptNoWatchdog, TimeProvider wallClock) => new()
    {
        Job = Job,
        Notes = notes,
        SampleId = sampleId,
        RepeatOf = ResumeFrom is null && ResumeLayers is null ? null : ContinuedFrom ?? lastRun,
        ResumeFrom = ResumeFrom,
        ResumeLayers = ResumeLayers,
        JobFile = Job.Layers is not null ? jobFile : null,
        AcceptNoWatchdog = acceptNoWatchdog,
        WallClock = wallClock,
    };
}

/// <summary>
/// The run bar's Continue and the run history's: whether the stopped run (or a logged one) can go on with the job as it
/// is now, and why not, in one line. It starts nothing itself: the run is its owner's to start (<see cref="RunOrder"/>).
/// </summary>
public sealed partial class RunContinueViewModel : ObservableObject
{
    private readonly IJobSession _job;
    private readonly MachineViewModel _machine;
    private readonly LogViewModel _log;
    private readonly LayersViewModel? _layers;
    private readonly RunProgressViewModel _bar;
    private readonly Func<RunOrder, Task> _run;

    internal RunContinueViewModel(IJobSession job, MachineViewModel machine, LogViewModel log, LayersViewModel? layers, RunProgressViewModel bar, Func<RunOrder, Task> run)
    {
        (_job, _machine, _log, _layers, _bar, _run) = (job, machine, log, layers, bar, run);
        _bar.PropertyChanged += (_, e) => Changed(reasons: e.PropertyName == nameof(RunProgressViewModel.StoppedAt), commands: e.PropertyName is nameof(RunProgressViewModel.State) or nameof(RunProgressViewModel.StoppedAt) or nameof(RunProgressViewModel.RunPlanVersion));
        _layers?.PropertyChanged += (_, e) => Changed(e.PropertyName is nameof(LayersViewModel.Job) or nameof(LayersViewModel.Layers));
        _machine.Activity.PropertyChanged += (_, e) => Changed(e.PropertyName == nameof(MachineActivity.Current));
        _job.PropertyChanged += (_, e) => Changed(reasons: e.PropertyName == nameof(IJobSession.PlanVersion), commands: true);
        _machine.PropertyChanged += (_, _) => Changed(reasons: false, commands: true);
    }

    /// <summary>The run that stopped last, and the comparison of the job now with the one it stopped on.</summary>
    internal StoppedRuns Stopped { get; } = new();

    /// <summary>Whether <see cref="ContinueCommand"/> can pick the stopped run up: the job as it stopped, nothing under way.</summary>
    public bool CanContinue => _bar.StoppedAt is not null && ContinueUnavailableReason is null;

    /// <summary>
    /// Why a stopped run cannot be continued now, one line (e.g. the job changed, naming what); null when it can, or when
    /// no run stopped. Setting the job back as it was offers Continue again.
    /// </summary>
    public string? ContinueUnavailableReason => _bar.StoppedAt is null ? null : WhyNotContinue();

    /// <summary>
    /// Continues the run that stopped (a fault or an abort) from its first burn run not completed, laser off on the way
    /// there, so the sample ends with no gap and nothing burned twice. Only with the plan it stopped on, while the job
    /// is as it was then; <see cref="ContinueUnavailableReason"/> says why not otherwise.
    /// </summary>
    [RelayCommand(CanExecute = nameof(CanContinue))]
    private async Task ContinueAsync()
    {
        if (_bar.IsActive)
        {
            _bar.Notice = "a run is already under way: this Continue was ignored";
            return;
        }

        _bar.Error = null;
        _bar.Notice = null;
        var stopped = Stopped.Last;
        var problem = _bar.StoppedAt is null || stopped is null ? "no stopped run to continue: the last run completed, or none ran"
            : WhyNotContinue();
        if (problem is not null)
        {
            _bar.Error = problem;
            return;
        }

        await _run(new RunOrder(stopped!.Job, stopped.Settings, stopped.Job.Layers is null ? stopped.StopPoint : null, stopped.LayerResume));
    }

    /// <summary>
    /// Why the logged run at <paramref name="path"/> cannot be continued from the run history now, one line; null when it
    /// can (a run that stopped with a stop point, made with the app's machine profile, a machine connected and free).
    /// </summary>
    public string? WhyNotContinueLogged(string path) =>
        StoppedRuns.WhyNotLogged(path, _log.Find(path)?.Record, _log.History, _job.Profile)
        ?? (_bar.IsActive ? "a run is already under way" : null)
        ?? _machine.Activity.BusyMessage
        ?? (_machine.Connection is null ? "not connected: connect to the machine the run stopped on first" : null);

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
        _bar.Error = null;
        _bar.Notice = null;
        if (WhyNotContinueLogged(path) is { } why)
        {
            _bar.Error = $"{Path.GetFileName(path)} cannot be continued: {why}";
            return;
        }

        var record = _log.Find(path)!.Record!;
        _log.LoadCommand.Execute(path);
        if (_log.Error is { } loadError)
        {
            _bar.Error = loadError;
            return;
        }

        // A drawing's stop point counts strokes, an image's rows: only a job of the logged kind can go on from it.
        var target = _job.Engraving is { } planned && planned is DrawingJob == record.Drawing is not null ? planned : null;
        var counts = target?.Planned ?? (-1, -1L);

        // The stop point counts the logged plan's moves: only the same plan, made again, can go on from it.
        if (target is null || counts != (record.RowsTotal, record.RunsTotal))
        {
            _bar.Error = $"{Path.GetFileName(path)} cannot be continued: the job planned from its log is not the one that ran ({(target is null ? "it does not plan" : $"{counts.Units} {record.RowsCounted} and {counts.Runs} runs, not {record.RowsTotal} and {record.RunsTotal}")}); Repeat runs it again";
            return;
        }

        // An older log's stop point may count an older planner's moves: where it stands in this plan (docs/run-log.md, "Older logs").
        var stop = target is RasterJob raster ? RunReplay.StopPointInPlan(record, () => raster.Prepared.Plan) : record.StoppedAt;
        await _run(new RunOrder(target, _job.ToSettings(), stop, ContinuedFrom: path));
    }

    private string? WhyNotContinue() =>
        _machine.Activity.BusyMessage
        ?? (_machine.Connection is null ? "not connected: connect to the machine the run stopped on first" : null)
        ?? Stopped.Difference((_job.PlanVersion, _layers?.PlanVersion ?? 0), new JobNow(_layers is { IsActive: true } ? _layers.Layers : null, _job.ToSettings, _job.Mask));

    // Something Continue depends on changed: its reasons are read again, its command asked again whether it can run.
    private void Changed(bool both) => Changed(both, both);

    private void Changed(bool reasons, bool commands)
    {
        if (reasons)
        {
            OnPropertyChanged(nameof(CanContinue));
            OnPropertyChanged(nameof(ContinueUnavailableReason));
        }

        if (commands)
        {
            ContinueCommand.NotifyCanExecuteChanged();
        }
    }
}
