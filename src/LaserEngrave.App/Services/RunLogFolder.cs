using LaserEngrave.Core.Logging;

namespace LaserEngrave.App.Services;

/// <summary>The real <see cref="IRunLogStore"/>: a <see cref="RunLogStore"/> on a folder.</summary>
public sealed class RunLogFolder(string folder) : IRunLogStore
{
    private readonly RunLogStore _store = new(folder);

    public string Folder => _store.Folder;

    public RunLogFiles Save(RunRecord record) => _store.Write(record);

    public void CheckWritable() => _store.CheckWritable();

    public IReadOnlyList<RunLogEntry> History() => _store.List();
}
