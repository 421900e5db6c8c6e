using LaserEngrave.Core.Logging;

namespace LaserEngrave.App.Services;

/// <summary>The real <see cref="IRunLogStore"/>: a <see cref="RunLogStore"/> on a folder.</summary>
/// <param name="folder">The run log folder.</param>
/// <param name="dataFolder">
/// The app's data folder: a run's log goes there (then to the temporary folder) when <paramref name="folder"/> fails during
/// the run, so the record that resumes it is never lost (<see cref="FallbackRunLogWriter"/>); null: no fallback.
/// </param>
/// <param name="files">The file operations; tests act a full or read-only disk with them.</param>
public sealed class RunLogFolder(string folder, string? dataFolder = null, RunLogFileSystem? files = null) : IRunLogStore
{
    private readonly RunLogStore _store = new(folder, files);

    public string Folder => _store.Folder;

    public RunLogFiles Save(RunRecord record) =>
        dataFolder is null ? _store.Write(record) : FallbackRunLogWriter.For(_store, dataFolder, files).Write(record);

    public void CheckWritable() => _store.CheckWritable();

    public IReadOnlyList<RunLogEntry> History() => _store.List();
}
