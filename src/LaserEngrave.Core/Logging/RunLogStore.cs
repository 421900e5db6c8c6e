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

    /// <summary>The room a run's log is checked for before the run: a log and its summary take 5-10 kB, a job of many layers more.</summary>
    public const int LogBudgetBytes = 256 * 1024;

    // A file being written has this suffix until it is complete: never listed, never read as a log.
    private const string PartialSuffix = ".partial";

    private readonly RunLogFileSystem _files;

    public RunLogStore(string folder, RunLogFileSystem? files = null)
    {
        ArgumentException.ThrowIfNullOrWhiteSpace(folder);
        Folder = Path.GetFullPath(folder);
        _files = files ?? RunLogFileSystem.Real;
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

    /// <summary>
    /// Before a run (before anything moves): the folder exists or can be made, takes a file, and has room for a log
    /// (<see cref="LogBudgetBytes"/>, written and removed again); throws <see cref="RunLogException"/> with one line otherwise.
    /// </summary>
    public void CheckWritable()
    {
        CreateFolder();
        var probe = Path.Combine(Folder, $".write-check-{Guid.NewGuid():N}{PartialSuffix}");
        try
        {
            using (var stream = _files.CreateNew(probe))
            {
                stream.Write(new byte[LogBudgetBytes]);
                Flush(stream);
            }
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            throw new RunLogException($"{Folder}: cannot write the run log there: {ex.Message}", ex);
        }
        finally
        {
            TryDelete(probe);
        }

        // What the probe took is free again; a disk that had just that much would be full by the log's time.
        if (_files.AvailableBytes(Folder) is { } free && free < LogBudgetBytes)
        {
            throw new RunLogException(string.Create(CultureInfo.InvariantCulture, $"{Folder}: the log folder's disk is full ({free / 1024} kB free, a run log needs up to {LogBudgetBytes / 1024} kB); free some space or choose another --log-dir"));
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
        // Both files are written whole under names no log has, then named: a full disk or a crash never leaves a
        // partial or empty log, only a .partial file, which is never read as one.
        var jsonTemp = WriteTemporary(stem + kind + ".json", json);
        string textTemp;
        try
        {
            textTemp = WriteTemporary(stem + kind + ".txt", summary);
        }
        catch
        {
            TryDelete(jsonTemp);
            throw;
        }

        try
        {
            for (var n = 1; n <= MaxSuffix; n++)
            {
                var name = n == 1 ? stem : string.Create(CultureInfo.InvariantCulture, $"{stem}-{n}");
                var files = new RunLogFiles(Path.Combine(Folder, name + kind + ".json"), Path.Combine(Folder, name + kind + ".txt"));
                if (_files.Exists(files.JsonPath) || _files.Exists(files.TextPath) || !TryName(jsonTemp, files.JsonPath))
                {
                    continue;
                }

                if (!TryName(textTemp, files.TextPath))
                {
                    // Another writer took the text name between the checks; give the pair up and take the next name.
                    _files.Move(files.JsonPath, jsonTemp);
                    continue;
                }

                return files;
            }
        }
        finally
        {
            TryDelete(jsonTemp);
            TryDelete(textTemp);
        }

        throw new RunLogException($"{Folder}: {MaxSuffix} logs are already named {stem}; choose another folder");
    }

    // Writes the content whole (to the disk) under a temporary name beside the final one; returns that name.
    private string WriteTemporary(string name, string content)
    {
        var path = Path.Combine(Folder, $".{name}.{Guid.NewGuid():N}{PartialSuffix}");
        try
        {
            using var stream = _files.CreateNew(path);
            stream.Write(Utf8.GetBytes(content));
            Flush(stream);
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            TryDelete(path);
            throw new RunLogException($"{Path.Combine(Folder, name)}: cannot write the run log: {ex.Message}", ex);
        }

        return path;
    }

    // Gives the complete file its name; false when the name is taken (by another writer since the check).
    private bool TryName(string temporary, string path)
    {
        try
        {
            _files.Move(temporary, path);
            return true;
        }
        catch (IOException) when (_files.Exists(path))
        {
            return false;
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            throw new RunLogException($"{path}: cannot write the run log: {ex.Message}", ex);
        }
    }

    // To the disk itself: a file named as a log is complete on the disk, whatever happens to the computer next.
    private static void Flush(Stream stream)
    {
        if (stream is FileStream file)
        {
            file.Flush(flushToDisk: true);
        }
        else
        {
            stream.Flush();
        }
    }

    private void TryDelete(string path)
    {
        try
        {
            if (_files.Exists(path))
            {
                _files.Delete(path);
            }
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            // A leftover .partial file is never read as a log.
        }
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
            text = IO.TextFile.Read(path);
        }
        catch (IO.TextEncodingException ex)
        {
            throw new RunLogException($"{path}: {ex.Message}", ex);
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

        // Letters and digits of any script stay (a sample "Muestra ñ-01 ±5 µm" keeps its ñ and µ: every file system the
        // app runs on takes them); anything else, separators and characters Windows refuses included, becomes one '_'.
        var safe = new StringBuilder();
        foreach (var ch in text.Trim().Normalize(NormalizationForm.FormC))
        {
            var keep = char.IsLetterOrDigit(ch) || ch is '-' or '.';
            if (!keep && safe.Length > 0 && safe[^1] == '_')
            {
                continue;
            }

            safe.Append(keep ? ch : '_');
            if (safe.Length == MaxSampleChars)
            {
                break;
            }
        }

        // A name of dots only (".", "..") would mean something else to the file system; Windows drops a trailing dot.
        return safe.ToString().Trim('.', '_');
    }
}
