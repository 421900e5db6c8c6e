using CommunityToolkit.Mvvm.ComponentModel;
using CommunityToolkit.Mvvm.Input;
using LaserEngrave.App.Services;

namespace LaserEngrave.App.ViewModels;

/// <summary>The Log view: notes and sample ID for the next run, the last run's summary, and the history of past runs.</summary>
public sealed partial class LogViewModel : ObservableObject
{
    private readonly IRunLogStore _store;
    private readonly IFileAccess _files;
    private readonly JobViewModel _job;

    public LogViewModel(IRunLogStore store, IFileAccess files, JobViewModel job)
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

    /// <summary>The run that ended last in this session.</summary>
    [ObservableProperty]
    public partial RunRecord? LastRun { get; private set; }

    [ObservableProperty]
    public partial IReadOnlyList<RunRecord> History { get; private set; } = [];

    [ObservableProperty]
    public partial string? Error { get; private set; }

    public string Folder => _store.Folder;

    /// <summary>Keeps a finished run and shows it as the last one.</summary>
    public void Record(RunRecord record)
    {
        ArgumentNullException.ThrowIfNull(record);
        LastRun = record;
        try
        {
            _store.Save(record);
            Error = null;
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            Error = $"the run log could not be saved in {_store.Folder}: {ex.Message}";
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
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            Error = $"the run history in {_store.Folder} cannot be read: {ex.Message}";
        }
    }

    public RunRecord? Find(string id) => History.FirstOrDefault(r => r.Id == id) ?? (LastRun?.Id == id ? LastRun : null);

    /// <summary>Puts a past run's image and settings back into the Image, Size and Process views.</summary>
    [RelayCommand]
    private void Load(string id)
    {
        Error = null;
        if (Find(id) is not { } record)
        {
            Error = $"run {id} is not in the history";
            return;
        }

        if (record.Settings.ImagePath is { } path && !_files.Exists(path))
        {
            Error = $"run {id}: its image {path} is no longer there; the settings were loaded without it";
            _job.Apply(record.Settings with { ImagePath = null });
            return;
        }

        _job.Apply(record.Settings);
        Notes = record.Notes;
        SampleId = record.SampleId;
    }

    [RelayCommand]
    private void OpenFolder()
    {
        try
        {
            _files.OpenFolder(_store.Folder);
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException or InvalidOperationException or System.ComponentModel.Win32Exception)
        {
            Error = $"cannot open {_store.Folder}: {ex.Message}";
        }
    }
}
