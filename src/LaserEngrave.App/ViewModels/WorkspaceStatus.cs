using System.Globalization;
using LaserEngrave.App.Components;
using LaserEngrave.Core.Jobs;

namespace LaserEngrave.App.ViewModels;

/// <summary>
/// What the workspace's header and run bar say of what Start would run: the sweep shown on the stage, else the layers,
/// else the single job. The choice the page once made in its markup, here so that it is tested and the page only renders it.
/// </summary>
public static class WorkspaceStatus
{
    /// <summary>The estimate of what Start runs, all passes, s; null without a plan.</summary>
    public static double? StartEstimateSeconds(MainViewModel main)
    {
        ArgumentNullException.ThrowIfNull(main);
        return main.Sweep is { ShowsOnStage: true, Plan: { } sweep } ? sweep.EstimatedSeconds
            : main.Layers.IsActive ? main.Layers.EstimatedSeconds
            : main.Job.EstimatedSeconds;
    }

    /// <summary>The header's line: the sweep's cells, the layers, or the job's size (a drawing named as one: its size is its own paths', not a pixel grid's), with the estimate.</summary>
    public static string Summary(MainViewModel main)
    {
        ArgumentNullException.ThrowIfNull(main);
        return main.Sweep is { ShowsOnStage: true, Plan: { } sweep }
            ? string.Create(CultureInfo.InvariantCulture, $"sweep {sweep.RowCount} × {sweep.ColumnCount} cells · est. {Format.Duration(sweep.EstimatedSeconds)}")
            : main.Layers.Engraving is { } layers
            ? string.Create(CultureInfo.InvariantCulture, $"{layers.Parts.Count} layers · est. {Format.Duration(layers.EstimatedSeconds)}")
            : main.Layers.IsActive ? "layers: see the Layers panel"
            : main.Job.Engraving is { Parts: [var job] } planned
            ? string.Create(CultureInfo.InvariantCulture, $"{(planned is DrawingJob ? "drawing " : "")}{job.SizeMm.WidthMm:0.##} × {job.SizeMm.HeightMm:0.##} mm · est. {Format.Duration(main.Job.EstimatedSeconds ?? 0)}")
            : main.Job.ImageInfo is null && !main.Job.IsDrawing ? "no image" : "no job: see the fields marked in red";
    }
}
