using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Marks;
using LaserEngrave.Core.Planning;
using LaserEngrave.Simulator.Marks;

namespace LaserEngrave.Machines.Marks;

/// <summary>
/// The one sequence that makes marks for every front end (`laserengrave mark` and the app's Mark panel): number the
/// copies from the counter, lay them out and draw them, plan them as a job of layers, prove every code on the twin when
/// asked, and only when every code reads set the counter's start and save the job.
/// </summary>
public static class MarkMaking
{
    /// <summary>Makes <paramref name="order"/> into a job in its folder.</summary>
    /// <returns>What was made; its <see cref="MadeMarks.JobFile"/> is null when a code did not read (nothing was saved then).</returns>
    /// <exception cref="MarkException">The mark cannot be made as asked (one line, in the front end's names).</exception>
    public static async Task<MadeMarks> MakeAsync(MarkOrder order, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(order);
        var name = order.Name ?? (field => field);
        var machine = order.Machine;
        if (order.StartAt is { } first)
        {
            MarkCounter.Check(first);
        }

        var layout = MarkLayout.Make(order.Spec, order.StartAt ?? order.Counter.Next(), order.Context, machine, order.Folder, order.Name);
        LayeredJob job;
        try
        {
            job = LayeredJob.Prepare(layout.Layers, machine);
        }
        catch (PlanException ex)
        {
            throw new MarkException(ex.Message, ex);
        }

        // MarkLayout refuses copies off the travel already; this holds for the layers as planned (their own margins).
        if (!job.FitsTravel)
        {
            throw new MarkException(FormattableString.Invariant($"the marks reach past the stage's travel ({machine.X.TravelMm:0.###} x {machine.Y.TravelMm:0.###} mm); move {name("originMm")} or make fewer columns"));
        }

        var verdicts = new List<ReadabilityVerdict>();
        double? smallest = null;
        if (order.Check)
        {
            var codeLayers = job.Layers.Where(l => l.Layer.Source.EndsWith(MarkLayout.CodeFileSuffix, StringComparison.Ordinal)).ToList();
            foreach (var (code, layer) in layout.Codes.Zip(codeLayers))
            {
                verdicts.Add(await MarkReadability.CheckAsync(code, machine, layer.Spec.Process, layer.Spec.Origin, cancellationToken: cancellationToken).ConfigureAwait(false));
            }

            if (order.Smallest && layout.Codes.Count > 0)
            {
                var firstCode = layout.Codes[0];
                var found = await MarkReadability.SmallestReadableAsync(
                    firstCode.Symbol.Kind, firstCode.Symbol.Text, order.Spec.ErrorCorrection, firstCode.QuietModules, machine, codeLayers[0].Spec.Process, codeLayers[0].Spec.Origin, cancellationToken: cancellationToken).ConfigureAwait(false);
                smallest = found?.ModuleUm;
            }
        }

        string? jobFile = null;
        if (verdicts.All(v => v.Reads))
        {
            // A new batch's start is written only with its job: a refused mark leaves the counter as it was.
            if (order.StartAt is { } start)
            {
                order.Counter.Set(start);
            }

            jobFile = layout.Save(order.Folder, order.Counter.Path);
        }

        return new MadeMarks(layout, job, jobFile, verdicts, smallest);
    }
}
