using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Marks;
using LaserEngrave.Core.Planning;
using LaserEngrave.Machines.Marks;
using LaserEngrave.Simulator.Marks;

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
        var counter = Counter;
        var layout = MarkLayout.Make(spec, counter.Next(), new MarkContext(0, sample, now, machine.Name), machine, folder, PanelName);
        LayeredJob job;
        try
        {
            job = LayeredJob.Prepare(layout.Layers, machine);
        }
        catch (PlanException ex)
        {
            throw new MarkException(ex.Message, ex);
        }

        if (!job.FitsTravel)
        {
            throw new MarkException("the marks reach past the stage's travel; move the origin or make fewer columns");
        }

        var verdicts = new List<ReadabilityVerdict>();
        if (check)
        {
            var codeLayers = job.Layers.Where(l => l.Layer.Source.EndsWith(MarkLayout.CodeFileSuffix, StringComparison.Ordinal)).ToList();
            foreach (var (code, layer) in layout.Codes.Zip(codeLayers))
            {
                verdicts.Add(await MarkReadability.CheckAsync(code, machine, layer.Spec.Process, layer.Spec.Origin, cancellationToken: cancellationToken).ConfigureAwait(false));
            }
        }

        var jobFile = verdicts.All(v => v.Reads) ? layout.Save(folder, counter.Path) : null;
        return new MarkResult(jobFile, layout.Marks, job.EstimatedSeconds, verdicts);
    }
}
