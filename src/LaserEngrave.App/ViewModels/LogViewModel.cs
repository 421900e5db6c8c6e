using CommunityToolkit.Mvvm.ComponentModel;
using CommunityToolkit.Mvvm.Input;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;

namespace LaserEngrave.App.ViewModels;

/// <summary>The Log view: notes and sample ID for the next run, the last run's summary, and the history of past runs.</summary>
/// <remarks>A run is named by its log file's path, which the history lists and the export and load take back.</remarks>
public sealed partial class LogViewModel : ObservableObject
{
    private readonly IRunLogStore _store;
    private readonly IFileAccess _files;
    private readonly IJobSession _job;

    public LogViewModel(IRunLogStore store, IFileAccess files, IJobSession job)
    {
        ArgumentNullException.ThrowIfNull(store);
        ArgumentNullException.ThrowIfNull(files);
        ArgumentNullException.ThrowIfNull(job);
        _store = store;
        _files = files;
        _job = job;
    }

    [ObservableProperty]
    public partial string? Notes { get; set; }

    [ObservableProperty]
    public partial string? SampleId { get; set; }

    /// <summary>The run that ended last in this session, with the path of its log (null when it could not be saved).</summary>
    [ObservableProperty]
    public partial RunLogEntry? LastRun { get; private set; }

    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(Rows), nameof(SelectedRows))]
    public partial IReadOnlyList<RunLogEntry> History { get; private set; } = [];

    /// <summary>What the history table is searched for (sample ID, file, kind, outcome, notes, date); empty: every run.</summary>
    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(Rows), nameof(SelectedRows))]
    public partial string? Search { get; set; }

    /// <summary>The column the history table is sorted by (one of <see cref="RunHistoryRow.Columns"/>'s first twelve).</summary>
    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(Rows))]
    public partial string SortColumn { get; private set; } = "started";

    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(Rows))]
    public partial bool SortDescending { get; private set; } = true;

    /// <summary>The runs ticked in the history table, by their log's path, for the export.</summary>
    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(SelectedRows))]
    [NotifyCanExecuteChangedFor(nameof(ClearSelectionCommand))]
    public partial IReadOnlySet<string> Selected { get; private set; } = new HashSet<string>();

    /// <summary>The history as the table shows it: every readable run that matches <see cref="Search"/>, in the chosen order.</summary>
    /// <remarks>Made once per change of the history, the search or the order: a render reads it several times.</remarks>
    public IReadOnlyList<RunHistoryRow> Rows
    {
        get
        {
            lock (_rowsLock)
            {
                return _rows ??= MakeRows();
            }
        }
    }

    /// <summary>The ticked runs still shown, in the table's order: what the CSV and JSON exports hold.</summary>
    public IReadOnlyList<RunHistoryRow> SelectedRows
    {
        get
        {
            lock (_rowsLock)
            {
                return _selectedRows ??= [.. Rows.Where(r => Selected.Contains(r.Path))];
            }
        }
    }

    // A run's end sets the history on its own thread while a render may be reading the rows.
    private readonly Lock _rowsLock = new();
    private IReadOnlyList<RunHistoryRow>? _rows;
    private IReadOnlyList<RunHistoryRow>? _selectedRows;

    partial void OnHistoryChanged(IReadOnlyList<RunLogEntry> value) => ForgetRows(all: true);

    partial void OnSearchChanged(string? value) => ForgetRows(all: true);

    partial void OnSortColumnChanged(string value) => ForgetRows(all: true);

    partial void OnSortDescendingChanged(bool value) => ForgetRows(all: true);

    partial void OnSelectedChanged(IReadOnlySet<string> value) => ForgetRows(all: false);

    private void ForgetRows(bool all)
    {
        lock (_rowsLock)
        {
            _rows = all ? null : _rows;
            _selectedRows = null;
        }
    }

    private List<RunHistoryRow> MakeRows()
    {
        var rows = RunHistoryRow.From(History).Where(r => r.Matches(Search));
        Func<RunHistoryRow, object?> key = SortColumn switch
        {
            "sample ID" => r => r.SampleId,
            "image or drawing" => r => r.Source,
            "size" => r => r.WidthMm * r.HeightMm,
            "origin" => r => (r.OriginXMm, r.OriginYMm),
            "process" => r => (r.BurnSpeedMmPerS, r.LaserFrequencyHz, r.PitchUm),
            "passes" => r => r.Passes,
            "outcome" => r => r.Outcome.ToString(),
            "duration" => r => r.ActualSeconds,
            "estimate" => r => r.EstimatedSeconds,
            _ => r => r.StartedAt,
        };
        return [.. SortDescending ? rows.OrderByDescending(key) : rows.OrderBy(key)];
    }

    /// <summary>The columns the table sorts by, as its headers name them.</summary>
    public static IReadOnlyList<string> SortColumns { get; } = ["started", "sample ID", "image or drawing", "size", "origin", "process", "passes", "outcome", "duration", "estimate"];

    /// <summary>Sorts the table by <paramref name="column"/>; the same column again turns the order round.</summary>
    [RelayCommand]
    private void Sort(string column)
    {
        if (!SortColumns.Contains(column))
        {
            return;
        }

        SortDescending = column == SortColumn ? !SortDescending : column is "started" or "duration" or "estimate";
        SortColumn = column;
    }

    /// <summary>Ticks or unticks the run logged at <paramref name="path"/> for the export.</summary>
    [RelayCommand]
    private void ToggleSelected(string path)
    {
        var selected = new HashSet<string>(Selected);
        if (!selected.Remove(path))
        {
            selected.Add(path);
        }

        Selected = selected;
    }

    /// <summary>Ticks every run the table shows (after the search).</summary>
    [RelayCommand]
    private void SelectShown() => Selected = new HashSet<string>(Selected.Concat(Rows.Select(r => r.Path)));

    [RelayCommand(CanExecute = nameof(HasSelection))]
    private void ClearSelection() => Selected = new HashSet<string>();

    private bool HasSelection() => Selected.Count > 0;

    /// <summary>The ticked runs as CSV (decimal comma: fields between semicolons) or as JSON, for the export.</summary>
    public string Export(string format, bool decimalComma) => string.Equals(format, "json", StringComparison.OrdinalIgnoreCase)
        ? RunHistoryRow.ToJson(SelectedRows)
        : RunHistoryRow.ToCsv(SelectedRows, decimalComma);

    [ObservableProperty]
    public partial string? Error { get; private set; }

    /// <summary>What to know about a past run just loaded, e.g. that it ran with another machine profile.</summary>
    [ObservableProperty]
    public partial string? Notice { get; private set; }

    public string Folder => _store.Folder;

    /// <summary>Before a run, before anything moves: the log folder takes a file and has room for a log; throws <see cref="RunLogException"/> otherwise.</summary>
    public void CheckWritable() => _store.CheckWritable();

    /// <summary>Where a run's log goes (the store's folder), for the run's <see cref="Devices.Execution.EngraveSession"/>.</summary>
    public IRunLogWriter Writer => new StoreWriter(_store);

    /// <summary>Saves a finished run's log and shows it as the last run.</summary>
    public void Record(RunRecord record)
    {
        ArgumentNullException.ThrowIfNull(record);
        RunLogFiles? files = null;
        Exception? error = null;
        try
        {
            files = _store.Save(record);
        }
        catch (Exception ex) when (ex is RunLogException or IOException or UnauthorizedAccessException)
        {
            error = ex;
        }

        Recorded(record, files, error);
    }

    /// <summary>Shows a run whose log was written (to <paramref name="files"/>), or could not be (<paramref name="error"/>), as the last run.</summary>
    public void Recorded(RunRecord record, RunLogFiles? files, Exception? error)
    {
        ArgumentNullException.ThrowIfNull(record);
        if (files is not null)
        {
            LastRun = new RunLogEntry(files.JsonPath, record, null);

            // A log folder that failed during the run: the one line says where the log went instead.
            Error = files.Notice;
        }
        else
        {
            var why = error?.Message ?? "no log was written";
            LastRun = new RunLogEntry(string.Empty, record, why);
            Error = $"the run log could not be saved in {_store.Folder}: {why}";
        }

        Refresh();
    }

    [RelayCommand]
    private void Refresh()
    {
        try
        {
            History = _store.History();
        }
        catch (Exception ex) when (ex is RunLogException or IOException or UnauthorizedAccessException)
        {
            Error = $"the run history in {_store.Folder} cannot be read: {ex.Message}";
        }
    }

    /// <summary>The logged run at <paramref name="path"/>, if the history or the last run has it.</summary>
    public RunLogEntry? Find(string path) =>
        History.FirstOrDefault(e => e.Path == path && e.Record is not null) ?? (LastRun?.Path == path && path.Length > 0 ? LastRun : null);

    /// <summary>Puts a past run's image and settings back into the Image, Size and Process views.</summary>
    /// <remarks>The image must still be there, unchanged (its SHA-256 is checked), or nothing is loaded and the reason is shown.</remarks>
    [RelayCommand]
    private void Load(string path)
    {
        Error = null;
        Notice = null;
        if (Find(path)?.Record is not { } record)
        {
            Error = $"{path}: not a run in the history";
            return;
        }

        try
        {
            var spec = RunReplay.ToJobSpec(record, path);
            _job.Apply(JobSettings.From(spec) with { Passes = 1 });
            // The app plans with its own profile (the one its machine connection uses); a run made with another one
            // would not be repeated exactly, so say so rather than switch the machine's profile behind the user's back.
            Notice = spec.Profile == _job.Profile
                ? null
                : $"this run used the machine profile \"{spec.Profile.Name}\"; the app plans with \"{_job.Profile.Name}\", so the repeat may differ (the command line's engrave --from-log uses the logged profile)";
            Notes = record.Notes;
            SampleId = record.SampleId;
        }
        catch (Exception ex) when (ex is RunLogException or MachineBusyException)
        {
            Error = ex.Message;
        }
    }

    [RelayCommand]
    private void OpenFolder()
    {
        try
        {
            Error = _files.OpenFolder(_store.Folder)
                ? null
                : $"no file manager can show the log folder here (no desktop session): its path is {_store.Folder}";
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException or InvalidOperationException or System.ComponentModel.Win32Exception)
        {
            Error = $"no file manager could open the log folder ({ex.Message}): its path is {_store.Folder}";
        }
    }

    private sealed class StoreWriter(IRunLogStore store) : IRunLogWriter
    {
        public RunLogFiles Write(RunRecord record) => store.Save(record);
    }
}
