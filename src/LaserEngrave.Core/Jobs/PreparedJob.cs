using System.Security.Cryptography;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Process;

namespace LaserEngrave.Core.Jobs;

/// <summary>A job ready to preview, estimate or engrave: the mask, its geometry on the stage, the plan and its figures.</summary>
public sealed class PreparedJob
{
    private PreparedJob(JobSpec spec, ImageInfo image, BitMask mask, GeometryReport geometry, RasterPlan plan, PlanStatistics statistics, DotPlan? dots)
    {
        Pulses = dots is null
            ? PulseFigures.For(spec.Process, spec.Profile.SpotDiameterUm, geometry.PitchUm)
            : PulseFigures.ForDots(spec.Process.PulsesPerDot, spec.Process.LaserFrequencyWholeHz, dots.DotSpacingUm, spec.Profile.SpotDiameterUm, geometry.PitchUm, spec.Process.PulseEnergyUj);
        Dots = dots;
        Spec = spec;
        Image = image;
        Mask = mask;
        Geometry = geometry;
        Plan = plan;
        Statistics = statistics;
        _program = new Lazy<RasterProgram>(() => new RasterProgram(Plan, Spec.Process, Spec.Profile.Gate));
    }

    private readonly Lazy<RasterProgram> _program;

    public JobSpec Spec { get; }

    public ImageInfo Image { get; }

    public BitMask Mask { get; }

    public GeometryReport Geometry { get; }

    public RasterPlan Plan { get; }

    /// <summary>The plan's figures; in dot mode the dot plan's (its engraving estimate <see cref="DotModeEstimate.TotalSeconds"/>).</summary>
    public PlanStatistics Statistics { get; }

    /// <summary>The program of a raster pass of this job: what the executor sends and the estimate interprets.</summary>
    /// <param name="timing">The timing model to plan strokes by (default: the plan's; a run that times itself with wider latencies gives its own).</param>
    /// <remarks>The plan's program is one object for the job's life: what it keeps for resuming (its estimates at each row) is made once, however often the job is resumed.</remarks>
    public RasterProgram Program(TimedSwitching? timing = null) => timing is null ? _program.Value : new(Plan, Spec.Process, Spec.Profile.Gate, timing);

    /// <summary>The dot plan in <see cref="PlanMode.Dots"/> (what the executor runs then); null in raster mode.</summary>
    public DotPlan? Dots { get; }

    /// <summary>Null when the job can be engraved as planned; otherwise why not, in one line (checked before anything opens).</summary>
    /// <remarks>A raster burn whose pulses come further apart than a pixel is one (<see cref="JobRules.PixelPulses"/>): some pixels would get none.</remarks>
    public string? EngraveProblem => Dots is { } dots ? dots.Problem : Plan.SwitchingProblem ?? PixelPulsesProblem;

    private string? PixelPulsesProblem => JobRules.PixelPulses(Pulses) is { } tooFew ? $"{JobField.Label(JobField.Frequency)} {MachineLimits.Text.N(Spec.Process.LaserFrequencyHz)} Hz {tooFew}" : null;

    /// <summary>What the process does per pulse and per pixel at this pitch and the profile's spot (seed 004).</summary>
    public PulseFigures Pulses { get; }

    /// <summary>Warnings of the geometry, of the plan and of the pulses, in that order.</summary>
    public IReadOnlyList<JobWarning> Warnings => [.. Geometry.Warnings, .. Plan.Warnings, .. Dots?.Warnings ?? [], .. Pulses.Warnings];

    /// <summary>Refuses a drawing where only images are taken (a drawing is a <see cref="PreparedDrawing"/>).</summary>
    /// <remarks>Without this a drawing would be refused as "not an image", which sends the user looking in the wrong place.</remarks>
    public static void RefuseDrawing(string path)
    {
        if (Vectors.DrawingReader.IsDrawing(path))
        {
            throw new Vectors.DrawingException($"{path}: a drawing is not an image; plan, preview, engrave and frame take drawings, this does not");
        }
    }

    /// <summary>Loads the image, builds the mask, resolves the geometry and plans; throws one-line typed errors.</summary>
    public static PreparedJob Prepare(JobSpec spec)
    {
        ArgumentNullException.ThrowIfNull(spec);
        RefuseDrawing(spec.ImagePath);

        spec.Mask.Validate();
        JobRules.Require(spec.Process, spec.Profile);
        var mask = MaskBuilder.FromFile(spec.ImagePath, spec.Mask, out var info);
        return Prepare(spec, info, mask);
    }

    /// <summary>Plans an already built mask (the app rebuilds the mask as a slider moves, then re-plans).</summary>
    public static PreparedJob Prepare(JobSpec spec, ImageInfo info, BitMask mask)
    {
        ArgumentNullException.ThrowIfNull(spec);
        ArgumentNullException.ThrowIfNull(info);
        ArgumentNullException.ThrowIfNull(mask);
        var geometry = GeometryResolver.Resolve(spec.Size, mask.Width, mask.Height, spec.Origin, spec.Profile);
        var dotMode = spec.Process.Mode == PlanMode.Dots;
        var timing = TimedSwitching.For(spec.Process, spec.Profile, geometry.Geometry.MicrostepUm);

        // In dot mode the raster plan is kept for the preview and the figures of the runs; it is not what is executed.
        var plan = new RasterPlan(
            mask,
            geometry.Geometry,
            spec.Plan,
            spec.Profile.ScanOffsetUmAt(spec.Process.BurnSpeedMmPerS),
            dotMode ? null : timing);
        var statistics = plan.ComputeStatistics(spec.Process, spec.Profile.Gate);
        DotPlan? dots = null;
        if (dotMode)
        {
            dots = new DotPlan(mask, geometry.Geometry, spec.Process, spec.Profile, spec.Plan);
            Dot? first = null, last = null;
            foreach (var dot in dots.Dots())
            {
                first ??= dot;
                last = dot;
            }

            // What is executed: every dot a stop with a burst, no burning in motion, no speed change.
            statistics = statistics with
            {
                Rows = dots.Estimate.Rows,
                Moves = dots.Estimate.Dots,
                BurnRuns = dots.Estimate.Dots,
                BurnLengthMm = 0,
                TravelLengthMm = dots.Estimate.TravelLengthMm,
                OverscanLengthMm = 0,
                LaserSwitches = dots.Estimate.Dots + 1,
                SpeedChanges = 0,
                EngravingSeconds = dots.Estimate.TotalSeconds,
                PreparationSeconds = first is { } a ? timing.PreparationSeconds(a.X, a.Y, home: true, from: (0, 0)) : 0,
                PassSetupSeconds = first is { } b && last is { } z ? timing.PreparationSeconds(b.X, b.Y, home: false, from: (z.X, z.Y)) : 0,
                Ends = first is { } f && last is { } l ? ((f.X, f.Y), (l.X, l.Y)) : null,
            };
        }

        return new PreparedJob(spec, info, mask, geometry, plan, statistics, dots);
    }

    /// <summary>SHA-256 of the image file, lower-case hex, for the run log.</summary>
    public static string HashFile(string path)
    {
        if (Core.IO.RegularFile.Problem(path) is { } problem)
        {
            throw new ImageLoadException(path, problem);
        }

        using var stream = File.OpenRead(path);
        return Convert.ToHexStringLower(SHA256.HashData(stream));
    }
}
