using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Marks;
using LaserEngrave.Machines.Marks;

namespace LaserEngrave.App.Services;

/// <summary>Marks made into marks/ in the app's data folder, numbered from the counter kept with the settings.</summary>
/// <param name="folders">The app's folders: the counter beside settings.json, the jobs under marks/.</param>
/// <param name="profile">The machine profile in force (its spot, process and travel).</param>
/// <param name="time">The lab's clock, for {date} and {time} and the jobs' folder names.</param>
public sealed class MarkService(AppFolders folders, Func<MachineProfile> profile, TimeProvider time) : IMarkService
{
    private MarkCounter Counter => new(Path.Combine(folders.DataFolder, MarkCounter.FileName));

    public int NextNumber() => Counter.Next();

    /// <summary>A marks file's field as the Mark panel labels it, so a refusal names the box to change.</summary>
    internal static string PanelName(string field) => field switch
    {
        "sizeMm" => "code size",
        "moduleUm" => "module size",
        "textHeightMm" => "text height",
        "originMm" => "origin",
        "pitchMm" => "pitch",
        "speedMmPerS" => "burn speed",
        "frequencyHz" => "laser frequency",
        _ => field,
    };

    public async Task<MarkResult> MakeAsync(MarkSpec spec, string? sample, bool check, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(spec);
        var machine = profile();
        var now = time.GetLocalNow();
        var folder = Path.Combine(folders.DataFolder, "marks", $"{now:yyyy-MM-dd_HHmmss}_{Guid.NewGuid().ToString("N")[..6]}");
        var order = new MarkOrder(spec, Counter, new MarkContext(0, sample, now, machine.Name), machine, folder) { Name = PanelName, Check = check };
        var made = await MarkMaking.MakeAsync(order, cancellationToken).ConfigureAwait(false);
        return new MarkResult(made.JobFile, made.Layout.Marks, made.Job.EstimatedSeconds, made.Verdicts);
    }
}
