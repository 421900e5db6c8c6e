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
    private readonly IJobSession _job;
    private readonly MachineViewModel _machine;
    private readonly IRunLogStore _logs;
    private readonly TimeProvider _time;
    private SweepSession? _session;

    public SweepViewModel(IJobSession job, MachineViewModel machine, IRunLogStore logs, TimeProvider time)
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
            if (e.PropertyName is nameof(IJobSession.PlanVersion) or nameof(IJobSession.Errors) or nameof(IJobSession.Profile)
                || (e.PropertyName is nameof(IJobSession.Mask) && Pattern == SweepPattern.Image))
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
                Origin = new OriginMm(_job.ToSettings().OriginXMm, _job.ToSettings().OriginYMm),
                Rows = SweepAxis.Parse(Rows ?? string.Empty, "Rows"),
                Columns = string.IsNullOrWhiteSpace(Columns) ? null : SweepAxis.Parse(Columns, "Columns"),
                Labels = Labels,
                Process = _job.Process(),
                Plan = _job.PlanOptions(),
                Profile = _job.Profile,
            });
            Error = null;

            // The cells this computer cannot hold with this gate, named before Run (a counting gate is taken to time its
            // switch-ons; the sweep asks it CAPS? before its first cell and refuses then if it does not).
            if (SweepSpeedHold.Problem(Plan.Cells, _job.Profile, scheduled: _job.Profile.Gate.CountsBursts) is { } tooFast)
            {
                Plan = null;
                Error = InPanelWords(tooFast);
            }
        }
        catch (Exception ex) when (ex is SweepException or PlanException or GeometryException)
        {
            Plan = null;
            Error = InPanelWords(ex.Message);
        }

        OnPropertyChanged(nameof(FocusAvailable));
        OnPropertyChanged(nameof(ParameterNames));
        OnPropertyChanged(nameof(FocusNote));
        OnPropertyChanged(nameof(ImageAvailable));
        FocalSeriesCommand.NotifyCanExecuteChanged();
    }

    /// <summary>The sweep's rules name the command line's options; the panel says its own fields' names instead.</summary>
    internal static string InPanelWords(string message) =>
        OptionWords.Aggregate(message, (text, pair) => text.Replace(pair.Option, pair.Field, StringComparison.Ordinal));

    private static readonly (string Option, string Field)[] OptionWords =
    [
        ("--pattern image needs the cell's image: --cell-image FILE", "the cells burn the job's image: load an image first (Image panel)"),
        ("--pattern image", "Cells \"the job's image\""),
        ("--cell-image", "the job's image"),
        ("--cell-mm", "Cell"),
        ("--spacing-mm", "Spacing"),
        ("--pitch-um", "Pitch"),
        ("--passes", "Passes (Process panel)"),
        ("move the sweep (--origin-mm)", "move the sweep (the job's Origin X and Y)"),
        ("--labels", "Burn the values beside rows and columns"),
        ("--focus-um", "Rows"),
        ("--rows", "Rows"),
        ("--columns", "Columns"),
        ("add --mode dots", "choose Mode: dots in the Process panel"),
    ];

    /// <summary>The plan in one line: cells, place and estimate.</summary>
    public string? Summary => Plan is { } plan
        ? string.Create(CultureInfo.InvariantCulture, $"{plan.RowCount} × {plan.ColumnCount} cells from {plan.Spec.Origin.X:0.##}, {plan.Spec.Origin.Y:0.##} mm · est. {Components.Format.Duration(plan.EstimatedSeconds)}")
        : null;

    partial void OnPlanChanged(SweepPlan? value)
    {
        OnPropertyChanged(nameof(Summary));

        // The last sweep's progress belongs to its plan, not to this one.
        if (!IsRunning)
        {
            Progress = null;
        }
    }

    partial void OnPatternChanged(SweepPattern value) => Replan();

    partial void OnCellMmChanged(double value) => Replan();

    partial void OnSpacingMmChanged(double value) => Replan();

    partial void OnPitchUmChanged(double value) => Replan();

    partial void OnRowsChanged(string value) => Replan();

    partial void OnColumnsChanged(string value) => Replan();

    partial void OnLabelsChanged(bool value) => Replan();

    /// <summary>The sweep under way: which job (the labels or a cell) and that job's own progress; null before the first report.</summary>
    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(Fraction), nameof(ProgressText), nameof(RemainingSeconds))]
    public partial SweepProgress? Progress { get; private set; }

    /// <summary>Share of the sweep done, 0..1: the jobs (labels and cells) ended, plus the share of the one under way.</summary>
    public double Fraction => Progress is { Jobs: > 0 } p ? Math.Clamp((p.Index + p.Run.Fraction) / p.Jobs, 0, 1) : 0;

    /// <summary>The plan's estimate of what is left, by the share of the sweep done (0 when none runs).</summary>
    public double RemainingSeconds => IsRunning && Plan is { } plan ? plan.EstimatedSeconds * (1 - Fraction) : 0;

    /// <summary>What burns now, counted as the panel's grid counts its cells: "cell 4 of 9: row 2, column 1 (speed 1 mm/s, …)", or the labels.</summary>
    public string? ProgressText => Progress is { } p && Plan is { } plan
        ? p.Cell is { } cell
            ? $"cell {CellNumber(p.Index, plan)} of {plan.Cells.Count}: {cell.Describe()["cell ".Length..]}"
            : $"the labels, then {plan.Cells.Count} cells"
        : null;

    /// <summary>The cell's number, from 1, in burn order; the labels (when there are labels) burn first and are no cell.</summary>
    private static int CellNumber(int jobIndex, SweepPlan plan) => jobIndex + 1 - (plan.Labels is null ? 0 : 1);

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
        var cells = plan.Cells.Count;
        var done = 0;
        session.JobEnded += (_, e) =>
        {
            var outcome = e.Result.Record.Outcome.ToString().ToLowerInvariant();
            Status = e.Cell is { } cell
                ? $"{++done} of {cells} cells done; {cell.Describe()}: {outcome}"
                : $"the labels: {outcome}; 0 of {cells} cells done";
        };
        _session = session;
        Progress = null;
        IsRunning = true;
        Status = $"0 of {cells} cells done";

        // The cells are the sweep job's parts in the order they burn (the labels first): the cross goes at their pace, as in a
        // run, on the machine's clock and where each cell's engine puts the stage.
        _pace = new LaserPace(SweepJob.Of(plan), connection.TimeProvider, session.StrokePositionAt);
        var paceTimer = _time.CreateTimer(_ => MoveLaser(), null, RunViewModel.PaceInterval, RunViewModel.PaceInterval);
        try
        {
            var result = await session.RunAsync(new LatestProgress(this), lease.CancellationToken);
            LastSweep = result.Record;
            Status = result.Record.Outcome == RunOutcome.Completed
                ? $"completed: {cells} of {cells} cells; log {result.Files?.JsonPath ?? result.LogError?.Message}"
                : $"{result.Record.Outcome.ToString().ToLowerInvariant()} after {done} of {cells} cells: {result.Record.Fault}";
        }
        finally
        {
            paceTimer.Dispose();
            lock (_paceLock)
            {
                _pace = null;
                LaserMicrosteps = null;
            }

            _session = null;
            IsRunning = false;
            try
            {
                // Each cell's preflight may have homed the stage: the Machine panel reads the state again.
                await _machine.RefreshStateAsync(CancellationToken.None);
            }
            catch (Exception ex) when (ex is Devices.Abstractions.DeviceException or InvalidOperationException or ObjectDisposedException or TimeoutException or IOException)
            {
                _machine.Error = ex.Message;
            }
        }
    }

    /// <summary>
    /// Where the stage drawing puts the laser while the sweep runs: the motion in flight at its planned pace between the
    /// engine's reports (see <see cref="LaserPace"/>); null when no sweep runs.
    /// </summary>
    [ObservableProperty]
    public partial (long X, long Y)? LaserMicrosteps { get; private set; }

    private LaserPace? _pace;

    // The pace's timer ticks on the pool: a tick never sets the drawn laser again once the sweep has cleared it.
    private readonly Lock _paceLock = new();

    private void MoveLaser()
    {
        lock (_paceLock)
        {
            if (_pace is { } pace && Progress is { } progress)
            {
                LaserMicrosteps = pace.Now(progress.Run.State == RunState.Running);
            }
        }
    }

    /// <summary>Laser off, stage stopped, no further cell.</summary>
    [RelayCommand(CanExecute = nameof(IsRunning))]
    private void AbortSweep() => _session?.Abort();

    /// <summary>Keeps only the newest report, and moves the laser's cross with it.</summary>
    private sealed class LatestProgress(SweepViewModel owner) : IProgress<SweepProgress>
    {
        public void Report(SweepProgress value)
        {
            owner.Progress = value;
            if (value.Run.State is RunState.Running && (owner._machine.XHomed is not true || owner._machine.YHomed is not true))
            {
                owner._machine.PreflightHomed();
            }

            owner._machine.XMicrosteps = value.Run.Run.XMicrosteps;
            owner._machine.YMicrosteps = value.Run.Run.YMicrosteps;
            if (owner._pace is { } pace)
            {
                // Each cell (the labels first) is a session of its own: its index picks the sweep job's part.
                pace.Report(value.Index + 1, value.Run.Pass, value.Run.MovesDone, value.Run.Run.XMicrosteps, value.Run.Run.YMicrosteps);
                owner.MoveLaser();
            }
        }
    }
}
