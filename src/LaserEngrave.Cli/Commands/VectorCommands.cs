using System.CommandLine;
using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Preview;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Cli.Commands;

/// <summary>`plan` and `preview` of a drawing (.dxf, .svg): the same commands as for images, branching here when the file is a drawing.</summary>
internal static class VectorCommands
{
    public static bool IsDrawing(ParseResult result, JobOptions job) =>
        result.GetValue(job.Image) is { } path && DrawingReader.IsDrawing(path);

    public static int Plan(ParseResult result, JobOptions job, VectorOptionSet vector, bool json, string? segmentsCsv)
    {
        var prepared = Prepare(result, job, vector);
        var plan = prepared.Plan;
        if (segmentsCsv is not null)
        {
            WriteSegments(plan, segmentsCsv);
        }

        var output = result.InvocationConfiguration.Output;
        var summary = VectorSummary.From(prepared);
        if (json)
        {
            CliJson.Write(output, summary);
        }
        else
        {
            summary.WriteText(output);
        }

        foreach (var warning in prepared.Warnings)
        {
            result.InvocationConfiguration.Error.WriteLine($"warning: {warning}");
        }

        return 0;
    }

    /// <summary>The drawing job from the options: read, placed, ordered, and its strokes planned; nothing opened.</summary>
    public static PreparedDrawing Prepare(ParseResult result, JobOptions job, VectorOptionSet vector)
    {
        var (spec, width) = job.BindDrawing(result);
        var options = vector.Bind(result);
        return width is null ? PreparedDrawing.PrepareOwnSize(spec, options) : PreparedDrawing.Prepare(spec, options);
    }

    public static int Preview(ParseResult result, JobOptions job, VectorOptionSet vector, string path, int maxPx)
    {
        var plan = Build(result, job, vector);
        VectorPreview.Render(plan, path, maxPx);
        result.InvocationConfiguration.Output.WriteLine(string.Create(
            CultureInfo.InvariantCulture,
            $"{path}: {plan.Paths.Count} paths, burn {plan.BurnLengthMm:0.###} mm, travel {plan.TravelMm:0.###} mm (black = burn, blue to purple = travel in order)"));
        WriteWarnings(result, plan);
        return 0;
    }

    private static VectorPlan Build(ParseResult result, JobOptions job, VectorOptionSet vector)
    {
        var path = result.GetValue(job.Image)!;
        if (result.GetValue(job.HeightMm) is not null || result.GetValue(job.PitchUm) is not null || result.GetValue(job.ImageDpi))
        {
            throw new UsageException($"{path}: a drawing is sized by --width-mm or by its own units; --height-mm, --pitch-um and --image-dpi are for images");
        }

        var width = result.GetValue(job.WidthMm);
        if (width is { } w && !(w > 0 && double.IsFinite(w)))
        {
            throw new UsageException($"--width-mm {w.ToString(CultureInfo.InvariantCulture)}: must be above 0");
        }

        var profile = result.GetValue(job.Profile) is { } profilePath ? MachineProfile.Load(profilePath) : MachineProfile.Default;
        var options = vector.Bind(result) with { WidthMm = width, Origin = JobOptions.ParseOrigin(result.GetValue(job.OriginMm)) };
        return VectorPlanner.Plan(path, options, profile);
    }

    private static void WriteWarnings(ParseResult result, VectorPlan plan)
    {
        foreach (var warning in plan.Warnings)
        {
            result.InvocationConfiguration.Error.WriteLine($"warning: {warning}");
        }
    }

    /// <summary>Every move as CSV, as `plan --segments` writes it for images: travel to each path, then each of its segments burned.</summary>
    private static void WriteSegments(VectorPlan plan, string path)
    {
        using var writer = new StreamWriter(path, append: false, new System.Text.UTF8Encoding(encoderShouldEmitUTF8Identifier: false));
        writer.Write("kind,x0,y0,x1,y1\n");
        var at = plan.Start;
        foreach (var p in plan.Paths)
        {
            if (p.Start != at)
            {
                writer.Write(string.Create(CultureInfo.InvariantCulture, $"travel,{at.X},{at.Y},{p.Start.X},{p.Start.Y}\n"));
            }

            for (var i = 1; i < p.Points.Count; i++)
            {
                writer.Write(string.Create(CultureInfo.InvariantCulture, $"burn,{p.Points[i - 1].X},{p.Points[i - 1].Y},{p.Points[i].X},{p.Points[i].Y}\n"));
            }

            at = p.End;
        }
    }
}
