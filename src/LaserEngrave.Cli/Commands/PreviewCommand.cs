using System.CommandLine;
using System.Globalization;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Preview;

namespace LaserEngrave.Cli.Commands;

/// <summary>`laserengrave preview IMAGE (size) --out PREVIEW.png`: the plan drawn as PNG, and optionally the mask as it will burn.</summary>
internal static class PreviewCommand
{
    public static Command Create()
    {
        var job = new JobOptions();
        var output = new Option<string>("--out") { Description = "PNG of the plan: burns black, travels blue to purple in path order", Required = true };
        var maskOut = new Option<string?>("--mask-out") { Description = "Also write the mask as it will be burned (black = burn)" };
        var size = new Option<int>("--max-px") { Description = "Longest side of the preview in pixels", DefaultValueFactory = _ => 1200 };
        var vector = new VectorOptionSet();
        var command = new Command("preview", "Draw the plan (and optionally the mask) to PNG; for a drawing (.dxf, .svg), its paths and travel");
        job.AddTo(command);
        vector.AddTo(command);
        command.Options.Add(output);
        command.Options.Add(maskOut);
        command.Options.Add(size);
        command.SetAction(result =>
        {
            var maxPx = result.GetValue(size);
            if (maxPx is < 16 or > 4096)
            {
                throw new UsageException($"--max-px {maxPx}: must be between 16 and 4096");
            }

            if (VectorCommands.IsDrawing(result, job))
            {
                return result.GetValue(maskOut) is null
                    ? VectorCommands.Preview(result, job, vector, result.GetValue(output)!, maxPx)
                    : throw new UsageException("--mask-out is for images: a drawing has no mask");
            }

            OptionChecks.OutputFile(result.GetValue(output), "--out");
            OptionChecks.OutputFile(result.GetValue(maskOut), "--mask-out");
            var prepared = PreparedJob.Prepare(job.Bind(result));
            var path = result.GetValue(output)!;
            PlanPreview.Render(prepared.Plan, path, maxPx);
            var console = result.InvocationConfiguration.Output;
            console.WriteLine(string.Create(CultureInfo.InvariantCulture, $"{path}: plan of {prepared.Statistics.Moves} moves, estimated {JobSummary.Duration(prepared.Statistics.WholeRunSeconds(prepared.Spec.Passes))}"));
            if (result.GetValue(maskOut) is { } maskPath)
            {
                MaskPreview.Render(prepared.Mask, maskPath, maxPx);
                console.WriteLine($"{maskPath}: mask as it will be burned");
            }

            foreach (var warning in prepared.Warnings)
            {
                result.InvocationConfiguration.Error.WriteLine($"warning: {warning.Message}");
            }

            return 0;
        });
        return command;
    }
}
