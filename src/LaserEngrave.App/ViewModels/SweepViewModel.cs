using System.Globalization;
using CommunityToolkit.Mvvm.ComponentModel;
using CommunityToolkit.Mvvm.Input;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Sweeps;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.App.ViewModels;

/// <summary>
/// The Sweep view: a test grid with one or two process values varied over its rows and columns, planned live from the
/// job's process and origin, run on the connected machine as the command line's <c>sweep</c> runs it (<see cref="SweepSession"/>).
/// </summary>
public sealed partial class SweepViewModel : ObservableObject
{
    private readonly JobViewModel _job;
    private readonly MachineViewModel _machine;
    private readonly IRunLogStore _logs;
    private readonly TimeProvider _time;
    private SweepSession? _session;

    public SweepViewModel(JobViewModel job, MachineViewModel machine, IRunLogStore logs, TimeProvider time)
    {
        ArgumentNullException.ThrowIfNull(job);
        ArgumentNullException.ThrowIfNull(machine);
        ArgumentNullException.ThrowIfNull(logs);
        ArgumentNullException.ThrowIfNull(time);
        _job = job;
        _machine = machine;
        _logs = logs;
        _time = time;
        _job.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName is nameof(JobViewModel.PlanVersion) or nameof(JobViewModel.Errors) or nameof(JobViewModel.Profile)
                || (e.PropertyName is nameof(JobViewModel.Mask) && Pattern == SweepPattern.Image))
            {
                Replan();
            }
        };
        _machine.PropertyChanged += (_, _) => RunSweepCommand.NotifyCanExecuteChanged();
        _machine.Activity.PropertyChanged += (_, _) => RunSweepCommand.NotifyCanExecuteChanged();
        Replan();
    }

    [ObservableProperty]
    public partial SweepPattern Pattern { get; set; } = SweepPattern.Square;

    [ObservableProperty]
    public partial double CellMm { get; set; } = 1;

    [ObservableProperty]
    public partial double SpacingMm { get; set; } = 0.5;

    [ObservableProperty]
    public partial double PitchUm { get; set; } = 50;

    /// <summary>What the rows vary, as the command line says it: <c>speed=0.5,1,2</c>.</summary>
    [ObservableProperty]
    public partial string Rows { get; set; } = "speed=0.5,1,2";

    /// <summary>What the columns vary; empty: one column.</summary>
    [ObservableProperty]
    public partial string Columns { get; set; } = "frequency=500,1000,2000";

    [ObservableProperty]
    public partial bool Labels { get; set; } = true;

    /// <summary>Asked to draw the sweep on the stage (its cells planned, each labelled) instead of the job, to check it before it runs.</summary>
    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(ShowsOnStage))]
    public partial bool ShowOnStage { get; set; }

    /// <summary>Whether the stage draws the sweep: planned, and asked for or under way.</summary>
    public bool ShowsOnStage => Plan is not null && (ShowOnStage || IsRunning);

    /// <summary>The sweep as planned from these values and the job's process and origin; null when a value is refused.</summary>
    [ObservableProperty]
    [NotifyCanExecuteChangedFor(nameof(RunSweepCommand))]
    [NotifyPropertyChangedFor(nameof(ShowsOnStage))]
    public partial SweepPlan? Plan { get; private set; }

    /// <summary>Why the sweep cannot be planned, one line.</summary>
    [ObservableProperty]
    public partial string? Error { get; private set; }

    /// <summary>What the sweep under way is doing, or how the last one ended.</summary>
    [ObservableProperty]
    public partial string? Status { get; private set; }

    [ObservableProperty]
    [NotifyCanExecuteChangedFor(nameof(RunSweepCommand), nameof(AbortSweepCommand), nameof(FocalSeriesCommand))]
    [NotifyPropertyChangedFor(nameof(ShowsOnStage))]
    public partial bool IsRunning { get; private set; }

    /// <summary>The last sweep's log (its cells with their values, places and runs).</summary>
    [ObservableProperty]
    public partial SweepRecord? LastSweep { get; private set; }

    public bool CanRun => Plan is not null && !IsRunning && _machine.CanUseMachine;

    /// <summary>Whether the machine has a focus (Z) axis, so the rows or columns may vary the focus.</summary>
    public bool FocusAvailable => _job.Profile.Z is not null;

    /// <summary>The parameters the rows and columns may vary, as the field's label lists them.</summary>
    public string ParameterNames => FocusAvailable ? "speed, frequency, passes, pulses-per-dot, pitch, focus" : "speed, frequency, passes, pulses-per-dot, pitch";

    /// <summary>What the focus parameter means on this machine, or why it is not offered.</summary>
    public string FocusNote => _job.Profile.Z is { } z
        ? string.Create(CultureInfo.InvariantCulture, $"focus: µm from the visible focus (Z {z.FocusMm:0.###} mm), within Z {z.MinMm:0.###}..{z.UpperMm:0.###} mm, e.g. focus=-200..200:50")
        : "Focus is not offered: this machine profile has no Z axis (add a \"z\" section, docs/machine-profile.md).";

    /// <summary>The cells burn the job's image (its larger side the cell's); false while no image is loaded.</summary>
    public bool ImageAvailable => _job.Mask is not null && !_job.IsDrawing;

    /// <summary>Sets up a focal series (seed 002): short lines at focus -200..200 µm in 50 µm steps, one column, labelled.</summary>
    [RelayCommand(CanExecute = nameof(CanPresetFocalSeries))]
    private void FocalSeries()
    {
        Pattern = SweepPattern.Lines;
        Columns = string.Empty;
        Labels = true;
        Rows = "focus=-200..200:50";
    }

    private bool CanPresetFocalSeries() => FocusAvailable && !IsRunning;

    /// <summary>Lays the sweep out again from the fields and the job's process and origin.</summary>
    public void Replan()
    {
        try
        {
            if (Pattern == SweepPattern.Image && !ImageAvailable)
            {
                throw new SweepException("the cells burn the job's image: load an image first (Image panel)");
            }

            Plan = SweepPlan.Build(new SweepSpec
            {
                Pattern = Pattern,
                CellImage = Pattern == SweepPattern.Image && !_job.IsDrawing ? _job.Mask : null,
                CellImageName = _job.ImagePath is { } path ? Path.GetFileName(path) : null,
                CellMm = CellMm,
                SpacingMm = SpacingMm,
                PitchUm = PitchUm,
                Origin = new OriginMm(_job.OriginXMm, _job.OriginYMm),
                Rows = SweepAxis.Parse(Rows ?? string.Empty, "rows"),
                Columns = string.IsNullOrWhiteSpace(Columns) ? null : SweepAxis.Parse(Columns, "columns"),
                Labels = Labels,
                Process = _job.Process(),
                Plan = _job.PlanOptions(),
                Profile = _job.Profile,
            });
            Error = null;
        }
        catch (Exception ex) when (ex is SweepException or PlanException or GeometryException)
        {
            Plan = null;
            Error = ex.Message;
        }

        OnPropertyChanged(nameof(FocusAvailable));
        OnPropertyChanged(nameof(ParameterNames));
        OnPropertyChanged(nameof(FocusNote));
        OnPropertyChanged(nameof(ImageAvailable));
        FocalSeriesCommand.NotifyCanExecuteChanged();
    }

    /// <summary>The plan in one line: cells, place and estimate.</summary>
    public string? Summary => Plan is { } plan
        ? string.Create(CultureInfo.InvariantCulture, $"{plan.RowCount} × {plan.ColumnCount} cells from {plan.Spec.Origin.X:0.##}, {plan.Spec.Origin.Y:0.##} mm · est. {plan.EstimatedSeconds:0} s")
        : null;

    partial void OnPlanChanged(SweepPlan? value) => OnPropertyChanged(nameof(Summary));

    partial void OnPatternChanged(SweepPattern value) => Replan();

    partial void OnCellMmChanged(double value) => Replan();

    partial void OnSpacingMmChanged(double value) => Replan();

    partial void OnPitchUmChanged(double value) => Replan();

    partial void OnRowsChanged(string value) => Replan();

    partial void OnColumnsChanged(string value) => Replan();

    partial void OnLabelsChanged(bool value) => Replan();

    /// <summary>Runs the sweep on the connected machine (the simulator's burn check per cell), then writes its log.</summary>
    [RelayCommand(CanExecute = nameof(CanRun))]
    private async Task RunSweep()
    {
        if (Plan is not { } plan || !_machine.IsConnected)
        {
            return;
        }

        if (!_machine.Activity.TryBegin(MachineOperation.Sweep, out var lease, out var refusal))
        {
            Status = refusal;
            return;
        }

        using var held = lease;
        var connection = _machine.RequireConnection();
        var machine = new EngraveMachine(connection.Stage, connection.Gate, connection.TimeProvider, connection.Description, connection.Description)
        {
            Simulated = connection.IsSimulated,
            Inspector = connection.IsSimulated ? connection.Inspector : null,
        };
        var session = new SweepSession(machine, plan, new SweepSessionOptions { Log = new RunLogStore(_logs.Folder), WallClock = _time });
        var jobs = plan.Cells.Count + (plan.Labels is null ? 0 : 1);
        var done = 0;
        session.JobEnded += (_, e) => Status = string.Create(CultureInfo.InvariantCulture, $"{++done} of {jobs} done: {e.Cell?.Describe() ?? "the labels"}: {e.Result.Record.Outcome.ToString().ToLowerInvariant()}");
        _session = session;
        IsRunning = true;
        Status = $"0 of {jobs} done";
        try
        {
            var result = await session.RunAsync(null, lease.CancellationToken);
            LastSweep = result.Record;
            Status = result.Record.Outcome == RunOutcome.Completed
                ? $"completed: {jobs} of {jobs}; log {result.Files?.JsonPath ?? result.LogError?.Message}"
                : $"{result.Record.Outcome.ToString().ToLowerInvariant()}: {result.Record.Fault}";
        }
        finally
        {
            _session = null;
            IsRunning = false;
        }
    }

    /// <summary>Laser off, stage stopped, no further cell.</summary>
    [RelayCommand(CanExecute = nameof(IsRunning))]
    private void AbortSweep() => _session?.Abort();
}
