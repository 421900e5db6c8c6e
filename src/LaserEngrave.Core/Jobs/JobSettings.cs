using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Jobs;

/// <summary>
/// Every value the user sets for a job, as the app's fields, the command line's options, a job file's layer, a sweep's
/// cell and a run log give it; <see cref="JobRules.Check"/> answers for all of them. A <see cref="ProcessPreset"/> is a
/// named subset of it.
/// </summary>
public sealed record JobSettings
{
    public string? ImagePath { get; init; }

    public double ThresholdPercent { get; init; } = 50;

    public DitherMethod Dither { get; init; } = DitherMethod.None;

    public bool Invert { get; init; }

    /// <summary>Quarter turns clockwise of the image on the stage, 0..3 (<see cref="MaskOptions.QuarterTurns"/>).</summary>
    public int QuarterTurns { get; init; }

    /// <summary>The image flipped left to right before it is turned.</summary>
    public bool MirrorX { get; init; }

    /// <summary>The image flipped top to bottom before it is turned.</summary>
    public bool MirrorY { get; init; }

    /// <summary>How the image becomes its burn mask: threshold, dither, invert, turn and mirror.</summary>
    public MaskOptions ToMask() => new()
    {
        ThresholdPercent = ThresholdPercent, Dither = Dither, Invert = Invert, QuarterTurns = QuarterTurns, MirrorX = MirrorX, MirrorY = MirrorY,
    };

    /// <summary>Which field decides the size: width, height, both or pitch.</summary>
    public SizeMode SizeMode { get; init; } = SizeMode.Width;

    public double WidthMm { get; init; } = 5;

    public double HeightMm { get; init; } = 5;

    public double PitchUm { get; init; } = 50;

    public double OriginXMm { get; init; } = 1;

    public double OriginYMm { get; init; } = 1;

    public double LaserFrequencyHz { get; init; } = 1000;

    public double BurnSpeedMmPerS { get; init; } = 1;

    public double TravelSpeedMmPerS { get; init; } = 4;

    public double AccelerationMmPerS2 { get; init; } = 50;

    public PlanStrategy Strategy { get; init; } = PlanStrategy.Optimized;

    public bool Bidirectional { get; init; } = true;

    public double OverscanMm { get; init; }

    public int Passes { get; init; } = 1;

    /// <summary>Energy of one pulse, µJ, when known (for the energy per pixel); null: not given.</summary>
    public double? PulseEnergyUj { get; init; }

    /// <summary>Raster (burn while moving) or dots (stop and fire a counted burst at each dot).</summary>
    public PlanMode Mode { get; init; } = PlanMode.Raster;

    /// <summary>Pulses at each dot in dot mode.</summary>
    public int PulsesPerDot { get; init; } = 1;

    /// <summary>Distance between dots along a run in dot mode, microsteps; 0: one dot at each pixel's centre.</summary>
    public long DotPitchMicrosteps { get; init; }

    /// <summary>Settle time at each dot before the burst, ms.</summary>
    public double DotSettleMs { get; init; }

    /// <summary>A drawing's paths: outlines, fill or both.</summary>
    public Core.Vectors.VectorFillMode DrawingFill { get; init; }

    /// <summary>A drawing's chord tolerance, µm.</summary>
    public double ToleranceUm { get; init; } = Core.Vectors.VectorOptions.Default.ToleranceUm;

    /// <summary>A drawing's fill pitch, µm.</summary>
    public double FillPitchUm { get; init; } = Core.Vectors.VectorOptions.Default.FillPitchUm;

    /// <summary>Only this layer of a drawing; null: every layer.</summary>
    public string? DrawingLayer { get; init; }

    /// <summary>A drawing's paths in its own order, unoptimised.</summary>
    public bool DrawingOrder { get; init; }

    /// <summary>
    /// A value's name as the page's field says it ("Width", "Pixel pitch"), from its name in the settings' JSON
    /// (<c>widthMm</c>); the JSON name itself for one the page has no field for.
    /// </summary>
    public static string FieldLabel(string jsonName) => jsonName switch
    {
        "imagePath" => "image",
        "thresholdPercent" => "Threshold",
        "dither" => "Dither",
        "invert" => "Invert",
        "quarterTurns" => "Rotate",
        "mirrorX" => "Mirror X",
        "mirrorY" => "Mirror Y",
        "sizeMode" => "which size field leads",
        "widthMm" => "Width",
        "heightMm" => "Height",
        "pitchUm" => "Pixel pitch",
        "originXMm" => "Origin X",
        "originYMm" => "Origin Y",
        "laserFrequencyHz" => "Laser frequency",
        "burnSpeedMmPerS" => "Burn speed",
        "travelSpeedMmPerS" => "Travel speed",
        "accelerationMmPerS2" => "Acceleration",
        "strategy" => "Strategy",
        "bidirectional" => "Bidirectional",
        "overscanMm" => "Overscan",
        "passes" => "Passes",
        "pulseEnergyUj" => "Pulse energy",
        "mode" => "Mode",
        "pulsesPerDot" => "Pulses per dot",
        "dotPitchMicrosteps" => "Dot pitch",
        "dotSettleMs" => "Settle at each dot",
        "drawingFill" => "the drawing's fill",
        "toleranceUm" => "Chord tolerance",
        "fillPitchUm" => "Fill pitch",
        "drawingLayer" => "the drawing's layer",
        "drawingOrder" => "the drawing's order",
        _ => jsonName,
    };

    /// <summary>These values with the image's threshold, dither, inversion, turn and mirror taken from <paramref name="mask"/>.</summary>
    public JobSettings WithMask(MaskOptions mask)
    {
        ArgumentNullException.ThrowIfNull(mask);
        return this with
        {
            ThresholdPercent = mask.ThresholdPercent,
            Dither = mask.Dither,
            Invert = mask.Invert,
            QuarterTurns = mask.QuarterTurns,
            MirrorX = mask.MirrorX,
            MirrorY = mask.MirrorY,
        };
    }

    /// <summary>The values of a job (e.g. one a run log repeats), as the page shows them.</summary>
    public static JobSettings From(JobSpec spec)
    {
        ArgumentNullException.ThrowIfNull(spec);
        var settings = From(spec.Process, spec.Plan).WithMask(spec.Mask) with
        {
            ImagePath = spec.ImagePath,
            OriginXMm = spec.Origin.X,
            OriginYMm = spec.Origin.Y,
            Passes = spec.Passes,
        };
        return spec.Size switch
        {
            SizeSpec.ByWidth w => settings with { SizeMode = SizeMode.Width, WidthMm = w.WidthMm },
            SizeSpec.ByHeight h => settings with { SizeMode = SizeMode.Height, HeightMm = h.HeightMm },
            SizeSpec.ByWidthAndHeight b => settings with { SizeMode = SizeMode.WidthAndHeight, WidthMm = b.WidthMm, HeightMm = b.HeightMm },
            SizeSpec.ByPitch p => settings with { SizeMode = SizeMode.Pitch, PitchUm = p.PitchUm },

            // The page has no resolution field: the pitch the resolution gives is the same size.
            SizeSpec.ByResolution r => settings with { SizeMode = SizeMode.Pitch, PitchUm = 25_400 / r.Dpi },
            _ => settings,
        };
    }

    /// <summary>The process and plan values of a job (a sweep's base, a job file's layer), every other value the default.</summary>
    public static JobSettings From(ProcessSettings process, PlanOptions? plan = null)
    {
        ArgumentNullException.ThrowIfNull(process);
        plan ??= PlanOptions.Default;
        return new JobSettings
        {
            LaserFrequencyHz = process.LaserFrequencyHz,
            BurnSpeedMmPerS = process.BurnSpeedMmPerS,
            TravelSpeedMmPerS = process.TravelSpeedMmPerS,
            AccelerationMmPerS2 = process.AccelerationMmPerS2,
            PulseEnergyUj = process.PulseEnergyUj,
            Mode = process.Mode,
            PulsesPerDot = process.PulsesPerDot,
            DotPitchMicrosteps = process.DotPitchMicrosteps,
            DotSettleMs = process.DotSettleMs,
            Strategy = plan.Strategy,
            Bidirectional = plan.Bidirectional,
            OverscanMm = plan.OverscanMm,
        };
    }
}
