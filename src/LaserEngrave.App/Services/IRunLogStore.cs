using LaserEngrave.Core.Logging;

namespace LaserEngrave.App.Services;

/// <summary>The run logs: Core's <see cref="RunLogStore"/> folder, the same the command line writes to.</summary>
public interface IRunLogStore
{
    /// <summary>The folder the logs are in, for "open the log folder".</summary>
    string Folder { get; }

    /// <summary>Writes the record and its text summary; throws <see cref="RunLogException"/> when the folder cannot take them.</summary>
    RunLogFiles Save(RunRecord record);

    /// <summary>Before a run: the folder takes a file and has room for a log; throws <see cref="RunLogException"/> otherwise.</summary>
    void CheckWritable();

    /// <summary>Newest first; unreadable files are listed with their error.</summary>
    IReadOnlyList<RunLogEntry> History();
}
