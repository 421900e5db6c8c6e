using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;

namespace LaserEngrave.App.Services;

/// <summary>Jobs of layers through Core's <see cref="JobFile"/> and <see cref="LayeredJob"/>: the command line's reader, writer and planner.</summary>
public sealed class JobFiles(AppFolders folders) : IJobFiles
{
    public string DefaultFolder => Path.Combine(folders.DataFolder, "jobs");

    public IReadOnlyList<JobLayer> Load(string path) => JobFile.Load(path);

    public void Save(string path, IReadOnlyList<JobLayer> layers)
    {
        Directory.CreateDirectory(Path.GetDirectoryName(Path.GetFullPath(path))!);
        JobFile.Save(path, layers);
    }

    public LayeredJob Prepare(IReadOnlyList<JobLayer> layers, MachineProfile profile) => LayeredJob.Prepare(layers, profile);

    public IReadOnlyList<string> SampleJobs()
    {
        var folder = Path.Combine(folders.SamplesFolder, "jobs");
        return Directory.Exists(folder) ? [.. Directory.EnumerateFiles(folder, "*.json").Order(StringComparer.OrdinalIgnoreCase)] : [];
    }
}
