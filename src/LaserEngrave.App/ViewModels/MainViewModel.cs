using System.Globalization;
using System.ComponentModel;
using CommunityToolkit.Mvvm.ComponentModel;
using CommunityToolkit.Mvvm.Input;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Calibration;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.App.ViewModels;

/// <summary>The whole window: one view-model per view, and the settings kept between starts.</summary>
public sealed partial class MainViewModel : ObservableObject
{
    private const int RecentFileCount = 8;

    private readonly ISettingsStore _settingsStore;
    private readonly IFileAccess _files;

    public MainViewModel(
        IImageService images,
        IMachineConnectionFactory machines,
        IRunService runs,
        IRunLogStore logs,
        ISettingsStore settings,
        IFileAccess files,
        TimeProvider time,
        MachineActivity activity,
        IJobFiles? jobFiles = null)
    {
        ArgumentNullException.ThrowIfNull(settings);
        ArgumentNullException.ThrowIfNull(files);
        _settingsStore = settings;
        _files = files;
        Settings = settings.Load();
        if (!Themes.Contains(Settings.Theme))
        {
            // A hand-edited settings file's unknown theme: the system's, as at the first start.
            Settings = Settings with { Theme = Themes[0] };
        }

        SampleImages = files.SampleImages();
        var (profile, profileError) = LoadProfile(Settings.ProfilePath);
        ProfileError = profileError;
        Activity = activity;
        Job = new JobViewModel(images, profile, activity);
        Machine = new MachineViewModel(machines, profile, activity)
        {
            UseSimulator = Settings.UseSimulator,
            StagePort = Settings.StagePort,
            LaserPort = Settings.LaserPort,
        };
        TestMoves = new TestMovesViewModel(Machine, Job);
        Log = new LogViewModel(logs, files, Job);
        Layers = new LayersViewModel(jobFiles ?? new JobFiles(AppFolders.Default), Job, activity);
        Run = new RunViewModel(runs, Job, Machine, Log, time, Layers)
        {
            // A hand-edited settings file's threshold out of range: the hour of the first start.
            AskAboveMinutes = AskAboveProblem(Settings.AskAboveMinutes) is null ? Settings.AskAboveMinutes : RunViewModel.DefaultAskAboveMinutes,
        };
        Sweep = new SweepViewModel(Job, Machine, logs, time);
        Machine.PropertyChanged += OnMachineChanged;
        Job.PropertyChanged += OnJobChanged;
        Layers.PropertyChanged += OnLayersChanged;

        // Another job file opened: a new history, as for another image.
        Layers.Opened += (_, _) => History.Reset(Snapshot());
    }

    /// <summary>Images to start with, shipped with the app, so a newcomer can engrave at once.</summary>
    public IReadOnlyList<string> SampleImages { get; }

    /// <summary>What holds the machine now (a run, homing, a test move), for every view to disable what it must.</summary>
    public MachineActivity Activity { get; }

    public JobViewModel Job { get; }

    public MachineViewModel Machine { get; }

    public TestMovesViewModel TestMoves { get; }

    public RunViewModel Run { get; }

    /// <summary>The job of layers being built or opened; while it has layers, Start runs them.</summary>
    public LayersViewModel Layers { get; }

    /// <summary>The parameter sweep (a test grid in one run).</summary>
    public SweepViewModel Sweep { get; }

    public LogViewModel Log { get; }

    /// <summary>The job's undo and redo, one step per committed change of its settings or of its layers.</summary>
    public EditHistory<WorkbenchState> History { get; } = new();

    // Set while undo or redo puts a state back: what that changes is the state put back, not a new edit.
    private bool _puttingBack;

    private WorkbenchState Snapshot() => new(Job.ImagePath is null ? null : Job.ToSettings(), Layers.Layers);

    private bool CanUndo => History.CanUndo && Job.LockedBecause is null;

    private bool CanRedo => History.CanRedo && Job.LockedBecause is null;

    /// <summary>Puts the job's settings back as they were before its last change (Ctrl+Z).</summary>
    [RelayCommand(CanExecute = nameof(CanUndo))]
    private void Undo()
    {
        if (History.Undo() is { } state)
        {
            PutBack(state);
        }
    }

    /// <summary>Makes the change undone last again (Ctrl+Y).</summary>
    [RelayCommand(CanExecute = nameof(CanRedo))]
    private void Redo()
    {
        if (History.Redo() is { } state)
        {
            PutBack(state);
        }
    }

    private void PutBack(WorkbenchState state)
    {
        _puttingBack = true;
        try
        {
            if (!state.Layers.SequenceEqual(Layers.Layers))
            {
                Layers.Restore(state.Layers);
            }

            // The snapshot is of this image: its path is left out so nothing is read again.
            if (state.Job is { } settings && settings != Job.ToSettings())
            {
                Job.Apply(settings with { ImagePath = null });
            }
        }
        finally
        {
            _puttingBack = false;
        }

        UndoCommand.NotifyCanExecuteChanged();
        RedoCommand.NotifyCanExecuteChanged();
    }

    private void OnLayersChanged(object? sender, PropertyChangedEventArgs e)
    {
        if (e.PropertyName == nameof(LayersViewModel.Layers) && !_puttingBack)
        {
            History.Record(Snapshot());
        }

        UndoCommand.NotifyCanExecuteChanged();
        RedoCommand.NotifyCanExecuteChanged();
    }

    [ObservableProperty]
    public partial AppSettings Settings { get; private set; }

    /// <summary>Why the saved machine profile was not used, if it was not.</summary>
    [ObservableProperty]
    public partial string? ProfileError { get; private set; }

    /// <summary>Why the settings could not be saved, if they could not.</summary>
    [ObservableProperty]
    public partial string? SettingsError { get; private set; }

    /// <summary>Why the last test pattern could not be made, if it could not.</summary>
    [ObservableProperty]
    public partial string? PatternError { get; private set; }

    /// <summary>
    /// Opens the bidirectional scan offset pattern as the job (docs/execution.md, "Scan offsets"): short vertical bars at
    /// a 25 µm pitch, every other row burned the other way, at the burn speed set, with a run-up long enough to reach it.
    /// Burned and looked at under the microscope, the bars' halves show any offset between the two directions, to be
    /// entered per speed in the profile's <c>scanOffsets</c>.
    /// </summary>
    /// <exception cref="MachineBusyException">A run, homing or a test move is under way.</exception>
    public bool LoadScanOffsetPattern()
    {
        Activity.ThrowIfJobLocked();
        var pattern = ScanOffsetPattern.Create(pitchUm: 25, barWidthUm: 200, barHeightUm: 500, bars: 5, gapUm: 300);
        string path;
        try
        {
            path = _files.SavePattern("scan-offset", pattern.ToMask());
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            PatternError = $"the scan offset pattern could not be written: {ex.Message}";
            return false;
        }

        PatternError = null;
        if (!Job.LoadImage(path))
        {
            return false;
        }

        var speed = Job.BurnSpeedMmPerS;
        var acceleration = Job.AccelerationMmPerS2;
        Job.Batch(() =>
        {
            Job.EditPitch(pattern.PitchUm);
            Job.Strategy = PlanStrategy.Optimized;
            Job.Bidirectional = true;

            // A run-up as long as the stage needs to reach the speed, so the bars' edges burn at it.
            Job.OverscanMm = Math.Max(0.01, Math.Ceiling(speed * speed / (2 * acceleration) * 100) / 100);
        });
        return true;
    }

    /// <summary>Opens the last image again, if it is still there: read and planned in the background, as the page opens one.</summary>
    /// <returns>The open under way (its progress in <see cref="JobViewModel.LoadingLine"/>); the app's start does not wait for it.</returns>
    public Task Restore()
    {
        Log.RefreshCommand.Execute(null);
        if (Settings.LastJob is { } lastJob)
        {
            Job.Apply(lastJob with { ImagePath = null });
        }

        // The last session's job as it was, its turn and mirrors too (another file opens upright).
        return Settings.RecentFiles.FirstOrDefault() is { } last && _files.Exists(last) ? Job.LoadImageAsync(last, upright: false) : Task.CompletedTask;
    }

    /// <summary>Uses <paramref name="profile"/>, saved at <paramref name="path"/>, from now on: the job plans with it, the next connection uses it, the settings remember it.</summary>
    /// <exception cref="MachineBusyException">A run, homing or a test move is under way: nothing is changed.</exception>
    /// <summary>
    /// Writes <paramref name="profile"/> to <paramref name="path"/> and uses it from now on (calibration, commissioning):
    /// refused before anything is written while a run, homing or test move fixes the job, so the file on disk always
    /// matches what the page says.
    /// </summary>
    /// <exception cref="MachineBusyException">An operation that fixes the job is under way: the file is untouched.</exception>
    /// <exception cref="IOException">The file cannot be written.</exception>
    public void SaveProfile(string path, MachineProfile profile)
    {
        ArgumentException.ThrowIfNullOrWhiteSpace(path);
        ArgumentNullException.ThrowIfNull(profile);
        WriteProfile(path, profile);
        UseProfile(path, profile);
    }

    /// <summary>Writes <paramref name="profile"/> to <paramref name="path"/> without putting it in use; refused (nothing
    /// written) while a run or another machine operation holds the interlock.</summary>
    public void WriteProfile(string path, MachineProfile profile)
    {
        ArgumentException.ThrowIfNullOrWhiteSpace(path);
        ArgumentNullException.ThrowIfNull(profile);
        Activity.ThrowIfJobLocked();
        Directory.CreateDirectory(Path.GetDirectoryName(Path.GetFullPath(path))!);
        profile.Save(path);
    }

    public void UseProfile(string path, MachineProfile profile)
    {
        ArgumentException.ThrowIfNullOrWhiteSpace(path);
        ArgumentNullException.ThrowIfNull(profile);
        Job.UseProfile(profile);
        Machine.Profile = profile;
        ProfileError = null;
        Save(Settings with { ProfilePath = path });
    }

    /// <summary>The longest threshold the long-run question takes, minutes: a week.</summary>
    public const double MaxAskAboveMinutes = 7 * 24 * 60;

    /// <summary>Why the last threshold typed for the long-run question was refused; null when it was taken.</summary>
    [ObservableProperty]
    public partial string? AskAboveError { get; private set; }

    /// <summary>
    /// Start (and the API's start) asks before a run estimated longer than <paramref name="minutes"/>; kept in the
    /// settings. 0 asks before every run.
    /// </summary>
    /// <returns>False, with nothing changed and <see cref="AskAboveError"/> saying why, for a value out of range.</returns>
    public bool SetAskAboveMinutes(double minutes)
    {
        if (AskAboveProblem(minutes) is { } problem)
        {
            AskAboveError = problem;
            return false;
        }

        AskAboveError = null;
        Run.AskAboveMinutes = minutes;
        if (minutes != Settings.AskAboveMinutes)
        {
            Save(Settings with { AskAboveMinutes = minutes });
        }

        return true;
    }

    private static string? AskAboveProblem(double minutes) =>
        double.IsFinite(minutes) && minutes >= 0 && minutes <= MaxAskAboveMinutes
            ? null
            : string.Create(CultureInfo.InvariantCulture, $"ask before runs longer than {minutes} min: give 0 (ask before every run) to {MaxAskAboveMinutes} min (a week)");

    /// <summary>The themes offered: the system's light or dark mode, or always light, or always dark.</summary>
    public static IReadOnlyList<string> Themes { get; } = ["system", "light", "dark"];

    /// <summary>Uses <paramref name="theme"/> (one of <see cref="Themes"/>) from now on and keeps it in the settings.</summary>
    /// <returns>False, with nothing changed, for any other value.</returns>
    public bool SetTheme(string? theme)
    {
        if (theme is null || !Themes.Contains(theme))
        {
            return false;
        }

        if (theme != Settings.Theme)
        {
            Save(Settings with { Theme = theme });
        }

        return true;
    }

    private static (MachineProfile Profile, string? Error) LoadProfile(string? path)
    {
        if (path is null)
        {
            return (MachineProfile.Default, null);
        }

        try
        {
            return (MachineProfile.Load(path), null);
        }
        catch (ProfileException ex)
        {
            return (MachineProfile.Default, ex.Message + "; using the built-in profile");
        }
    }

    private void OnJobChanged(object? sender, PropertyChangedEventArgs e)
    {
        if (e.PropertyName == nameof(JobViewModel.LockedBecause))
        {
            UndoCommand.NotifyCanExecuteChanged();
            RedoCommand.NotifyCanExecuteChanged();
        }

        if (e.PropertyName == nameof(JobViewModel.ImagePath))
        {
            History.Reset(null);
        }
        else if (e.PropertyName == nameof(JobViewModel.PlanVersion))
        {
            // Each plan follows a committed change; putting a snapshot back plans it again, which records nothing new.
            if (!_puttingBack)
            {
                History.Record(Snapshot());
            }
            UndoCommand.NotifyCanExecuteChanged();
            RedoCommand.NotifyCanExecuteChanged();
        }

        if (e.PropertyName == nameof(JobViewModel.ImagePath) && Job.ImagePath is { } path)
        {
            var recent = Settings.RecentFiles.Where(f => f != path).Prepend(path).Take(RecentFileCount).ToList();
            Save(Settings with { RecentFiles = recent, LastFolder = Path.GetDirectoryName(path) });
        }
        else if (e.PropertyName == nameof(JobViewModel.PlanVersion) && Job.ImagePath is not null)
        {
            // Size, position and process as they were last planned, for the next start; written only when they changed.
            var job = Job.ToSettings() with { ImagePath = null };
            if (job != Settings.LastJob)
            {
                Save(Settings with { LastJob = job });
            }
        }
    }

    private void OnMachineChanged(object? sender, PropertyChangedEventArgs e)
    {
        if (e.PropertyName == nameof(MachineViewModel.Connection) && Machine.Connection is not null)
        {
            Save(Settings with { UseSimulator = Machine.UseSimulator, StagePort = Machine.StagePort, LaserPort = Machine.LaserPort });
        }
    }

    /// <summary>The decimal mark the number fields show: the one the user last typed (kept between starts).</summary>
    public char DecimalMark => Settings.DecimalComma ? ',' : '.';

    /// <summary>Takes the decimal mark from a number the user typed and read: a comma or a point; none (a whole number) changes nothing.</summary>
    public void NoteDecimalMark(string typed)
    {
        ArgumentNullException.ThrowIfNull(typed);
        var comma = typed.Contains(',', StringComparison.Ordinal);
        if (comma == Settings.DecimalComma || (!comma && !typed.Contains('.', StringComparison.Ordinal)))
        {
            return;
        }

        Save(Settings with { DecimalComma = comma });
        OnPropertyChanged(nameof(DecimalMark));
    }

    /// <summary>A number as the fields show it: up to <paramref name="decimals"/> decimals, no thousands separator, the user's decimal mark.</summary>
    public string ShowNumber(double value, int decimals = 4)
    {
        var text = Math.Round(value, decimals).ToString("0." + new string('#', decimals), CultureInfo.InvariantCulture);
        return DecimalMark == ',' ? text.Replace('.', ',') : text;
    }

    private void Save(AppSettings settings)
    {
        Settings = settings;
        try
        {
            _settingsStore.Save(settings);
            SettingsError = null;
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            SettingsError = $"settings not saved: {ex.Message}";
        }
    }
}
