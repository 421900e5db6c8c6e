using System.Globalization;
using System.Text;

namespace LaserEngrave.Core.Logging;

/// <summary>A folder of run logs: writes each run as a JSON record and a text summary, never overwriting; lists and reads them back.</summary>
/// <remarks>
/// File names are the start time (local, with seconds) and the sample ID, e.g. 2026-11-23_143005_S17.json and .txt;
/// a name already taken gets -2, -3 ... so two runs never share or overwrite a file.
/// </remarks>
public sealed class RunLogStore : IRunLogWriter, ISweepLogWriter
{
    /// <summary>The name of the folder under the user's documents.</summary>
    public const string FolderName = "LaserEngrave";

    private const int MaxSampleChars = 40;
    private const int MaxSuffix = 10_000;
    private static readonly UTF8Encoding Utf8 = new(encoderShouldEmitUTF8Identifier: false);

    public RunLogStore(string folder)
    {
        ArgumentException.ThrowIfNullOrWhiteSpace(folder);
        Folder = Path.GetFullPath(folder);
    }

    /// <summary>The folder the logs go to.</summary>
    public string Folder { get; }

    /// <summary>LaserEngrave under the user's documents (see <see cref="DefaultFolderFrom"/> for the fallbacks).</summary>
    public static string DefaultFolder => DefaultFolderFrom(Environment.GetFolderPath, Environment.CurrentDirectory);

    /// <summary>
    /// The default folder from the platform's folders: Documents/LaserEngrave; where the platform names no documents
    /// folder (a Linux account without one), ~/Documents/LaserEngrave; with no home either, LaserEngrave in the current directory.
    /// </summary>
    public static string DefaultFolderFrom(Func<Environment.SpecialFolder, string> folderPath, string currentDirectory)
    {
        ArgumentNullException.ThrowIfNull(folderPath);
        var documents = folderPath(Environment.SpecialFolder.MyDocuments);
        if (!string.IsNullOrEmpty(documents))
        {
            return Path.Combine(documents, FolderName);
        }

        var home = folderPath(Environment.SpecialFolder.UserProfile);
        return !string.IsNullOrEmpty(home)
            ? Path.Combine(home, "Documents", FolderName)
            : Path.Combine(currentDirectory, FolderName);
    }

    /// <summary>Creates the folder if needed; throws <see cref="RunLogException"/> when it cannot be, so a run can refuse to start without a place for its log.</summary>
    public void CreateFolder()
    {
        try
        {
            Directory.CreateDirectory(Folder);
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            throw new RunLogException($"{Folder}: cannot create the log folder: {ex.Message}", ex);
        }
    }

    /// <summary>Writes the record and its summary as two new files; throws <see cref="RunLogException"/> when the folder cannot take them.</summary>
    public RunLogFiles Write(RunRecord record)
    {
        ArgumentNullException.ThrowIfNull(record);
        CreateFolder();

        return WritePair(FileStem(record), RunRecordJson.Serialize(record), RunSummaryText.Format(record));
    }

    /// <summary>Writes a sweep's log as <c>STEM.sweep.json</c> and <c>.sweep.txt</c> (each cell's run inside it); <see cref="List"/> leaves them out.</summary>
    public RunLogFiles WriteSweep(SweepRecord record)
    {
        ArgumentNullException.ThrowIfNull(record);
        CreateFolder();
        var stem = record.StartedAt.ToString("yyyy-MM-dd_HHmmss", CultureInfo.InvariantCulture);
        var sample = SafeName(record.SampleId);
        return WritePair((sample.Length == 0 ? stem : $"{stem}_{sample}"), SweepRecord.Serialize(record), SweepRecord.Format(record), ".sweep");
    }

    private RunLogFiles WritePair(string stem, string json, string summary, string kind = "")
    {
        for (var n = 1; n <= MaxSuffix; n++)
        {
            var name = n == 1 ? stem : string.Create(CultureInfo.InvariantCulture, $"{stem}-{n}");
            var files = new RunLogFiles(Path.Combine(Folder, name + kind + ".json"), Path.Combine(Folder, name + kind + ".txt"));
            if (File.Exists(files.JsonPath) || File.Exists(files.TextPath) || !TryCreate(files.JsonPath, json))
            {
                continue;
            }

            if (!TryCreate(files.TextPath, summary))
            {
                // Another writer took the text name between the checks; give the pair up and take the next name.
                File.Delete(files.JsonPath);
                continue;
            }

            return files;
        }

        throw new RunLogException($"{Folder}: {MaxSuffix} logs are already named {stem}; choose another folder");
    }

    /// <summary>The runs in the folder, newest first; files that cannot be read are listed with their error, after the others.</summary>
    public IReadOnlyList<RunLogEntry> List()
    {
        if (!Directory.Exists(Folder))
        {
            return [];
        }

        var entries = new List<RunLogEntry>();
        foreach (var path in Directory.EnumerateFiles(Folder, "*.json"))
        {
            if (path.EndsWith(".sweep.json", StringComparison.OrdinalIgnoreCase))
            {
                // A sweep's log holds its cells' runs; it is read with SweepRecord, not listed as one run.
                continue;
            }

            try
            {
                entries.Add(new RunLogEntry(path, Read(path), null));
            }
            catch (RunLogException ex)
            {
                entries.Add(new RunLogEntry(path, null, ex.Message));
            }
        }

        return
        [
            .. entries
                .OrderBy(e => e.Record is null)
                .ThenByDescending(e => e.Record?.StartedAt)
                .ThenBy(e => e.Path, StringComparer.Ordinal),
        ];
    }

    /// <summary>
    /// Reads a record from its JSON file (or from the .txt summary's path, taking the .json beside it);
    /// throws <see cref="RunLogException"/> with one line for a missing, unreadable or invalid file.
    /// </summary>
    public static RunRecord Read(string path)
    {
        ArgumentException.ThrowIfNullOrWhiteSpace(path);
        if (path.EndsWith(".txt", StringComparison.OrdinalIgnoreCase) && File.Exists(Path.ChangeExtension(path, ".json")))
        {
            path = Path.ChangeExtension(path, ".json");
        }

        if (IO.RegularFile.Problem(path) is { } problem)
        {
            throw new RunLogException($"{path}: {problem}");
        }

        string text;
        try
        {
            text = File.ReadAllText(path, Utf8);
        }
        catch (Exception ex) when (ex is FileNotFoundException or DirectoryNotFoundException)
        {
            throw new RunLogException($"{path}: no such run log", ex);
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            throw new RunLogException($"{path}: cannot read the run log: {ex.Message}", ex);
        }

        return RunRecordJson.Deserialize(text, path);
    }

    /// <summary>The file name without extension: start time (to the second, in the record's offset) and the sample ID made safe for any file system.</summary>
    public static string FileStem(RunRecord record)
    {
        ArgumentNullException.ThrowIfNull(record);
        var stem = record.StartedAt.ToString("yyyy-MM-dd_HHmmss", CultureInfo.InvariantCulture);
        var sample = SafeName(record.SampleId);
        return sample.Length == 0 ? stem : $"{stem}_{sample}";
    }

    private static string SafeName(string? text)
    {
        if (string.IsNullOrWhiteSpace(text))
        {
            return string.Empty;
        }

        var safe = new StringBuilder();
        foreach (var ch in text.Trim())
        {
            safe.Append(char.IsAsciiLetterOrDigit(ch) || ch is '-' or '_' or '.' ? ch : '_');
            if (safe.Length == MaxSampleChars)
            {
                break;
            }
        }

        // A name of dots only (".", "..") would mean something else to the file system.
        return safe.ToString().Trim('.');
    }

    private static bool TryCreate(string path, string content)
    {
        FileStream stream;
        try
        {
            stream = new FileStream(path, FileMode.CreateNew, FileAccess.Write, FileShare.None);
        }
        catch (IOException) when (File.Exists(path))
        {
            return false;
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            throw new RunLogException($"{path}: cannot write the run log: {ex.Message}", ex);
        }

        using (stream)
        {
            var bytes = Utf8.GetBytes(content);
            stream.Write(bytes);
            stream.Flush(flushToDisk: true);
        }

        return true;
    }
}
