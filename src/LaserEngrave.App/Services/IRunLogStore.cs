namespace LaserEngrave.App.Services;

/// <summary>The history of runs.</summary>
public interface IRunLogStore
{
    /// <summary>The folder the logs are in, for "open the log folder".</summary>
    string Folder { get; }

    void Save(RunRecord record);

    /// <summary>Newest first.</summary>
    IReadOnlyList<RunRecord> History();
}
