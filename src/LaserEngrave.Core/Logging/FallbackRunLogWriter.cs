namespace LaserEngrave.Core.Logging;

/// <summary>
/// Writes a run's log where it was asked to go and, when that folder fails (full, read-only, turned into a file during the
/// run), to the first fallback folder that takes it: the record is the only thing that resumes a run, so it must not be lost.
/// </summary>
/// <remarks>
/// The fallbacks are folders the user can find: the program's data folder, then the temporary folder
/// (<see cref="FallbackFolders"/>). The files returned carry <see cref="RunLogFiles.FallbackReason"/>, so the front end says
/// where the log went in one line, first.
/// </remarks>
public sealed class FallbackRunLogWriter : IRunLogWriter
{
    private readonly IRunLogWriter _primary;
    private readonly string _primaryFolder;
    private readonly IReadOnlyList<RunLogStore> _fallbacks;

    public FallbackRunLogWriter(IRunLogWriter primary, string primaryFolder, IEnumerable<RunLogStore> fallbacks)
    {
        ArgumentNullException.ThrowIfNull(primary);
        ArgumentException.ThrowIfNullOrEmpty(primaryFolder);
        ArgumentNullException.ThrowIfNull(fallbacks);
        _primary = primary;
        _primaryFolder = Path.GetFullPath(primaryFolder);
        // A fallback that is the folder that failed would only fail again.
        _fallbacks = [.. fallbacks.Where(f => !SameFolder(f.Folder, _primaryFolder)).DistinctBy(f => f.Folder)];
    }

    /// <summary>A <see cref="RunLogStore"/> folder with the default fallbacks of <see cref="FallbackFolders"/>.</summary>
    public static FallbackRunLogWriter For(RunLogStore store, string dataFolder, RunLogFileSystem? files = null)
    {
        ArgumentNullException.ThrowIfNull(store);
        return new FallbackRunLogWriter(store, store.Folder, FallbackFolders(dataFolder).Select(f => new RunLogStore(f, files)));
    }

    /// <summary>Where a log goes when its folder fails: <paramref name="dataFolder"/>, then LaserEngrave in the temporary folder.</summary>
    public static IReadOnlyList<string> FallbackFolders(string dataFolder)
    {
        ArgumentException.ThrowIfNullOrEmpty(dataFolder);
        return [dataFolder, Path.Combine(Path.GetTempPath(), RunLogStore.FolderName)];
    }

    /// <summary>The data folder of the command line: the app's (LaserEngrave in the user's application data), so the app's run history is near.</summary>
    public static string DefaultDataFolder
    {
        get
        {
            var appData = Environment.GetFolderPath(Environment.SpecialFolder.ApplicationData);
            return Path.Combine(string.IsNullOrEmpty(appData) ? Path.GetTempPath() : appData, RunLogStore.FolderName);
        }
    }

    /// <summary>Writes to the primary folder, else to the first fallback that takes it; throws <see cref="RunLogException"/> naming every folder's problem when none does.</summary>
    public RunLogFiles Write(RunRecord record)
    {
        ArgumentNullException.ThrowIfNull(record);
        RunLogException primaryError;
        try
        {
            return _primary.Write(record);
        }
        catch (Exception ex) when (ex is RunLogException or IOException or UnauthorizedAccessException)
        {
            primaryError = ex as RunLogException ?? new RunLogException($"{_primaryFolder}: cannot write the run log: {ex.Message}", ex);
        }

        var problems = new List<string>();
        foreach (var fallback in _fallbacks)
        {
            try
            {
                return fallback.Write(record) with { FallbackReason = primaryError.Message };
            }
            catch (Exception ex) when (ex is RunLogException or IOException or UnauthorizedAccessException)
            {
                problems.Add(ex.Message);
            }
        }

        throw problems.Count == 0
            ? primaryError
            : new RunLogException($"{primaryError.Message}; nor in a fallback folder: {string.Join("; ", problems)}", primaryError);
    }

    private static bool SameFolder(string a, string b) =>
        string.Equals(
            Path.TrimEndingDirectorySeparator(Path.GetFullPath(a)),
            Path.TrimEndingDirectorySeparator(Path.GetFullPath(b)),
            OperatingSystem.IsWindows() || OperatingSystem.IsMacOS() ? StringComparison.OrdinalIgnoreCase : StringComparison.Ordinal);
}
