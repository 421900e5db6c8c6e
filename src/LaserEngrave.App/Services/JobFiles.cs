using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;

namespace LaserEngrave.App.Services;

/// <summary>Jobs of layers through Core's <see cref="JobFile"/> and <see cref="LayeredJob"/>: the command line's reader, writer and planner.</summary>
/// <param name="folders">The app's folders: the jobs, and the sample counter a job file's marks number from.</param>
/// <param name="profile">The machine profile in force, which a job file's marks are drawn for; null: the default.</param>
/// <param name="time">The lab's clock, for a mark's {date} and {time}; null: the system's.</param>
public sealed class JobFiles(AppFolders folders, Func<MachineProfile>? profile = null, TimeProvider? time = null) : IJobFiles
{
    public string DefaultFolder => Path.Combine(folders.DataFolder, "jobs");

    /// <remarks>A mark layer is made with the counter beside the settings, as the Mark panel's; {sample} is refused (no run's sample yet).</remarks>
    public IReadOnlyList<JobLayer> Load(string path) =>
        JobFile.Load(path, new Core.Marks.JobMarks(
            Path.Combine(folders.DataFolder, Core.Marks.MarkCounter.FileName), profile?.Invoke() ?? MachineProfile.Default, (time ?? TimeProvider.System).GetLocalNow(), null));

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
