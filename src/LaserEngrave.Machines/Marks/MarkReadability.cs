using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Marks;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Devices.LaserGate;
using LaserEngrave.Devices.Zaber;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Marks;

namespace LaserEngrave.Machines.Marks;

/// <summary>
/// Proves a code readable before it is burned: the code alone is run on a fresh twin (its motion, timed switching and
/// latency model, in virtual time), every pulse the twin fired is drawn as a disc of the spot's diameter from the dose
/// map, and ZXing reads the picture. The twin does not flatter: a picture that reads only because of a lucky threshold
/// is not made; a pulse burns its whole spot.
/// </summary>
public static class MarkReadability
{
    /// <summary>Runs <paramref name="code"/> on the twin at <paramref name="origin"/> with <paramref name="process"/> and reads it back.</summary>
    /// <param name="options">The twin's options (its seed, latencies); the defaults when null.</param>
    public static async Task<ReadabilityVerdict> CheckAsync(
        CodeRaster code,
        MachineProfile profile,
        ProcessSettings process,
        OriginMm origin,
        SimulatorOptions? options = null,
        CancellationToken cancellationToken = default)
    {
        ArgumentNullException.ThrowIfNull(code);
        ArgumentNullException.ThrowIfNull(profile);
        ArgumentNullException.ThrowIfNull(process);
        var spec = new JobSpec
        {
            ImagePath = $"code \"{code.Symbol.Text}\"",
            Size = SizeSpec.Width(code.WidthMm),
            Origin = origin,
            Process = process,
            Profile = profile,
        };
        var info = new ImageInfo(spec.ImagePath, ImageFormat.Bmp, 1, 1, code.Mask.Width, code.Mask.Height, 0, null, null, RowOrder.TopDown, "none", false);
        var job = PreparedJob.Prepare(spec, info, code.Mask);

        var machine = SimulatedMachine.CreateInProcess(profile, options);
        await using (machine.ConfigureAwait(false))
        {
            var stage = new ZaberChain(new ZaberConnection(machine.StageLink, machine.TimeProvider), profile);
            var gate = new PicLaserGate(machine.LaserLink, profile.Gate, machine.TimeProvider);
            RunResult result;
            try
            {
                result = await machine.RunAsync(() => new RunExecutor(stage, gate, job, machine.TimeProvider).RunAsync(cancellationToken)).ConfigureAwait(false);
            }
            finally
            {
                // On the simulation's loop, without ConfigureAwait(false): leaving the loop would leave its virtual time standing.
                await machine.RunAsync(async () =>
                {
                    await stage.DisposeAsync();
                    await gate.DisposeAsync();
                }).ConfigureAwait(false);
            }

            if (result.Outcome != RunOutcome.Completed)
            {
                throw new MarkException($"the twin did not complete the code \"{code.Symbol.Text}\": {result.FaultMessage ?? result.Outcome.ToString()}");
            }

            var report = machine.Recorder.Analyze(BurnGrid.For(job.Plan.Geometry), job.Mask, process.BurnSpeedMmPerS);
            var burned = Burned(report.Dose, job.Plan.Geometry.PitchMicrosteps * profile.X.MicrostepUm, profile.SpotDiameterUm);
            var decoded = CodeDecoder.Decode(burned, code.Symbol.Kind);
            var (right, worst) = Modules(burned, code);
            return new ReadabilityVerdict(
                code.Symbol.Text,
                decoded == code.Symbol.Text,
                decoded,
                code.ModuleUm,
                profile.SpotDiameterUm,
                right,
                code.Symbol.Size * code.Symbol.Size,
                worst,
                result.Duration.TotalSeconds,
                result.EstimatedSeconds);
        }
    }

    /// <summary>
    /// The smallest module, among the spot's diameter times 1, 1.1, 1.25, 1.5, 1.75, 2, 2.5, 3, 4 and 5, at which the
    /// code of <paramref name="text"/> still reads on the twin; null when none of them does.
    /// </summary>
    public static async Task<(double ModuleUm, ReadabilityVerdict Verdict)?> SmallestReadableAsync(
        CodeKind kind,
        string text,
        char? errorCorrection,
        int quietModules,
        MachineProfile profile,
        ProcessSettings process,
        OriginMm origin,
        SimulatorOptions? options = null,
        CancellationToken cancellationToken = default)
    {
        var symbol = CodeSymbol.Encode(kind, text, errorCorrection);
        foreach (var factor in new[] { 1, 1.1, 1.25, 1.5, 1.75, 2, 2.5, 3, 4, 5 })
        {
            var moduleUm = profile.SpotDiameterUm * factor;
            var verdict = await CheckAsync(CodeRaster.Render(symbol, moduleUm, quietModules, profile.SpotDiameterUm), profile, process, origin, options, cancellationToken).ConfigureAwait(false);
            if (verdict.Reads)
            {
                return (moduleUm, verdict);
            }
        }

        return null;
    }

    /// <summary>The burned picture at the dose map's resolution: every sub-cell within a spot's radius of a pulse is burned.</summary>
    /// <param name="pitchUm">The job's pixel pitch (a sub-cell is a quarter of it).</param>
    public static BitMask Burned(DoseMap dose, double pitchUm, double spotDiameterUm)
    {
        ArgumentNullException.ThrowIfNull(dose);
        var cellUm = pitchUm / DoseMap.SubcellsPerPixel;
        var radius = spotDiameterUm / 2 / cellUm;
        var reach = (int)Math.Ceiling(radius);
        var disc = new List<(int X, int Y)>();
        for (var j = -reach; j <= reach; j++)
        {
            for (var i = -reach; i <= reach; i++)
            {
                if ((i * i) + (j * j) <= radius * radius)
                {
                    disc.Add((i, j));
                }
            }
        }

        var burned = new BitMask(dose.Width, dose.Height);
        for (var y = 0; y < dose.Height; y++)
        {
            for (var x = 0; x < dose.Width; x++)
            {
                if (dose[x, y] == 0)
                {
                    continue;
                }

                foreach (var (i, j) in disc)
                {
                    var bx = x + i;
                    var by = y + j;
                    if (bx >= 0 && by >= 0 && bx < burned.Width && by < burned.Height)
                    {
                        burned[bx, by] = true;
                    }
                }
            }
        }

        return burned;
    }

    /// <summary>How many modules came out on the right side of half, and the worst module's share that is as it should be, %.</summary>
    private static (int Right, double WorstPercent) Modules(BitMask burned, CodeRaster code)
    {
        var cells = (double)burned.Width / code.Mask.Width * code.PixelsPerModule;
        var right = 0;
        var worst = 100.0;
        for (var my = 0; my < code.Symbol.Size; my++)
        {
            for (var mx = 0; mx < code.Symbol.Size; mx++)
            {
                var x0 = (int)Math.Round((mx + code.QuietModules) * cells);
                var y0 = (int)Math.Round((my + code.QuietModules) * cells);
                var x1 = (int)Math.Round((mx + code.QuietModules + 1) * cells);
                var y1 = (int)Math.Round((my + code.QuietModules + 1) * cells);
                var on = 0;
                for (var y = y0; y < y1; y++)
                {
                    for (var x = x0; x < x1; x++)
                    {
                        on += burned[x, y] ? 1 : 0;
                    }
                }

                var fraction = (double)on / Math.Max(1, (x1 - x0) * (y1 - y0));
                var asIntended = code.Symbol.Modules[mx, my] ? fraction : 1 - fraction;
                right += asIntended > 0.5 ? 1 : 0;
                worst = Math.Min(worst, 100 * asIntended);
            }
        }

        return (right, worst);
    }
}
