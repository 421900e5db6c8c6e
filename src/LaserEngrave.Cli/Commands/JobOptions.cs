using System.CommandLine;
using LaserEngrave.Core.Input;
using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Cli.Commands;

/// <summary>The options that define a job (image, mask, size, origin, plan, process, profile), shared by every command that plans.</summary>
internal sealed class JobOptions
{
    public Argument<string> Image { get; } = new("IMAGE") { Description = "Image file: BMP, PNG, GIF or PBM/PGM/PPM" };

    public MaskOptionSet Mask { get; } = new();

    public Option<double?> WidthMm { get; } = new("--width-mm") { Description = "Width of the engraving in mm (aspect kept)" };

    public Option<double?> HeightMm { get; } = new("--height-mm") { Description = "Height of the engraving in mm (aspect kept)" };

    public Option<double?> PitchUm { get; } = new("--pitch-um") { Description = "Pixel pitch in µm" };

    public Option<bool> ImageDpi { get; } = new("--image-dpi") { Description = "Use the image's own resolution for the size" };

    public Option<string?> OriginMm { get; } = new("--origin-mm") { Description = "Stage position of the image's top-left corner, X,Y in mm (default 0,0)" };

    public Option<string> Strategy { get; } = new("--strategy")
    {
        Description = "paper (every run its own move, as seed 000) or optimized",
        DefaultValueFactory = _ => "optimized",
    };

    public Option<bool> Bidirectional { get; } = new("--bidirectional") { Description = "Serpentine rows (the default)" };

    public Option<bool> Unidirectional { get; } = new("--unidirectional") { Description = "Every row left to right" };

    public Option<double> OverscanMm { get; } = new("--overscan-mm") { Description = "Laser-off run-up before and after each burn run, mm" };

    public Option<string?> Profile { get; } = new("--profile") { Description = "Machine profile (JSON); default: two Zaber T-LA60A" };

    public Option<double?> FrequencyHz { get; } = new("--frequency-hz") { Description = "Laser Q-switch frequency while burning, Hz" };

    public Option<double?> SpeedMmS { get; } = new("--speed-mm-s") { Description = "Burn speed, mm/s" };

    public Option<double?> TravelSpeedMmS { get; } = new("--travel-speed-mm-s") { Description = "Travel speed with the laser off, mm/s" };

    public Option<double?> AccelerationMmS2 { get; } = new("--acceleration-mm-s2") { Description = "Acceleration, mm/s²" };

    public Option<string?> Mode { get; } = new("--mode") { Description = "raster (burn while moving, the default) or dots (stop at each dot and fire a counted burst)" };

    public Option<int?> PulsesPerDot { get; } = new("--pulses-per-dot") { Description = "Pulses fired at each dot in --mode dots (default 1)" };

    public Option<long?> DotPitchMicrosteps { get; } = new("--dot-pitch-microsteps") { Description = "Distance between dots along a run, microsteps, in --mode dots (default: one dot at each pixel's centre)" };

    public Option<double?> DotSettleMs { get; } = new("--dot-settle-ms") { Description = "Time the stage is left to settle at each dot before the burst, ms (default 0)" };

    public void AddTo(Command command)
    {
        command.Arguments.Add(Image);
        Mask.AddTo(command);
        foreach (var option in new Option[]
        {
            WidthMm, HeightMm, PitchUm, ImageDpi, OriginMm, Strategy, Bidirectional, Unidirectional, OverscanMm,
            Profile, FrequencyHz, SpeedMmS, TravelSpeedMmS, AccelerationMmS2, Mode, PulsesPerDot, DotPitchMicrosteps, DotSettleMs,
        })
        {
            command.Options.Add(option);
        }
    }

    /// <summary>Reads the options into a job spec; throws <see cref="UsageException"/> naming the bad value.</summary>
    /// <remarks>Every number is checked against the machine profile's limits here, before any port opens.</remarks>
    public JobSpec Bind(ParseResult result)
    {
        var profile = BindProfile(result);
        var image = result.GetValue(Image) ?? throw new UsageException("IMAGE is required");
        var limits = MachineLimits.Of(profile);
        var process = BindProcess(result, profile);
        var origin = ParseOrigin(result.GetValue(OriginMm));
        OptionChecks.Refuse(JobSettings.From(process) with { OriginXMm = origin.X, OriginYMm = origin.Y }, limits, JobField.OriginX, JobField.OriginY);
        var size = BindSize(result, image, limits);
        RefusePitchBelowMicrostep(size, image, origin, profile);
        var spec = new JobSpec
        {
            ImagePath = image,
            Mask = Mask.Bind(result),
            Size = size,
            Origin = origin,
            Plan = BindPlan(result, limits),
            Process = process,
            Profile = profile,
        };

        // Every value once more together, as the app's fields and a run log are checked; a pitch from the image's resolution is named by it.
        if (JobRules.Check(JobSettings.From(spec), limits).FirstOrDefault() is { } problem)
        {
            throw new UsageException(problem.Field == JobField.Pitch && size is SizeSpec.ByResolution r
                ? $"--image-dpi ({OptionChecks.N(r.Dpi)} dpi) gives pixels of {problem.ValueText} µm: {problem.Rule}"
                : OptionChecks.Describe(problem));
        }

        return spec;
    }

    /// <summary>The machine profile the options name (the default one without --profile).</summary>
    public MachineProfile BindProfile(ParseResult result) =>
        result.GetValue(Profile) is { } path ? MachineProfile.Load(path) : MachineProfile.Default;

    /// <summary>Speeds, acceleration, frequency and the dot-mode values, each checked against the profile's limits.</summary>
    public ProcessSettings BindProcess(ParseResult result, MachineProfile profile)
    {
        var process = BindDots(result, ProcessSettings.FromProfile(profile) with
        {
            BurnSpeedMmPerS = result.GetValue(SpeedMmS) ?? profile.BurnSpeedMmPerS,
            TravelSpeedMmPerS = result.GetValue(TravelSpeedMmS) ?? profile.TravelSpeedMmPerS,
            AccelerationMmPerS2 = result.GetValue(AccelerationMmS2) ?? profile.AccelerationMmPerS2,
            LaserFrequencyHz = result.GetValue(FrequencyHz) ?? profile.LaserFrequencyHz,
        });
        OptionChecks.Refuse(JobSettings.From(process), MachineLimits.Of(profile), OptionChecks.ProcessFields);
        return process;
    }

    /// <summary>Adds the process options (not the image, size or mask ones) to a command that makes its own jobs.</summary>
    public void AddProcessTo(Command command)
    {
        foreach (var option in new Option[]
        {
            Strategy, Bidirectional, Unidirectional, OverscanMm, Profile, FrequencyHz, SpeedMmS, TravelSpeedMmS, AccelerationMmS2,
            Mode, PulsesPerDot, DotPitchMicrosteps, DotSettleMs,
        })
        {
            command.Options.Add(option);
        }
    }

    /// <summary>
    /// Reads the options of a drawing's job: width (or the drawing's own size when null), origin, process and profile;
    /// the image-only options (and dot mode) are refused with one line.
    /// </summary>
    public (JobSpec Spec, double? WidthMm) BindDrawing(ParseResult result)
    {
        var drawing = result.GetValue(Image) ?? throw new UsageException("IMAGE is required");
        if (new Option[] { HeightMm, PitchUm, ImageDpi }.FirstOrDefault(o => OptionChecks.IsGiven(result, o)) is { } sizeOption)
        {
            throw new UsageException($"{drawing}: a drawing is sized by --width-mm or by its own units; {sizeOption.Name} is for images");
        }

        if (new Option[] { Mask.Threshold, Mask.Dither, Mask.Invert, Strategy, Bidirectional, Unidirectional, OverscanMm, Mode, PulsesPerDot, DotPitchMicrosteps, DotSettleMs }
            .FirstOrDefault(o => OptionChecks.IsGiven(result, o)) is { } imageOption)
        {
            throw new UsageException($"{drawing}: {imageOption.Name} is for images; a drawing's paths are burned as they are");
        }

        var width = result.GetValue(WidthMm);
        var profile = BindProfile(result);
        var process = BindProcess(result, profile);
        var origin = ParseOrigin(result.GetValue(OriginMm));
        OptionChecks.Refuse(
            JobSettings.From(process) with
            {
                ImagePath = drawing,
                SizeMode = width is null ? SizeMode.Height : SizeMode.Width,
                WidthMm = width ?? 0,
                OriginXMm = origin.X,
                OriginYMm = origin.Y,
            },
            MachineLimits.Of(profile));
        var spec = new JobSpec
        {
            ImagePath = drawing,
            Size = SizeSpec.Width(width ?? 1),
            Origin = origin,
            Process = process,
            Profile = profile,
        };
        return (spec, width);
    }

    /// <summary>Refuses a size whose pixels would be smaller than one microstep, the smallest step the stage makes (whole pixels would vanish).</summary>
    private static void RefusePitchBelowMicrostep(SizeSpec size, string image, OriginMm origin, MachineProfile profile)
    {
        PreparedJob.RefuseDrawing(image);
        var info = ImageLoader.ReadInfo(image);
        var pitch = GeometryResolver.Resolve(size, info.Width, info.Height, origin, profile).PitchUm;
        if (JobRules.ResolvedPitch(pitch, MachineLimits.Of(profile)) is { } rule)
        {
            var given = size switch
            {
                SizeSpec.ByWidth w => $"--width-mm {OptionChecks.N(w.WidthMm)}",
                SizeSpec.ByHeight h => $"--height-mm {OptionChecks.N(h.HeightMm)}",
                SizeSpec.ByWidthAndHeight wh => $"--width-mm {OptionChecks.N(wh.WidthMm)} --height-mm {OptionChecks.N(wh.HeightMm)}",
                SizeSpec.ByResolution r => $"--image-dpi ({OptionChecks.N(r.Dpi)} dpi)",
                _ => size.Describe(),
            };
            throw new UsageException($"{given} for {info.Width} x {info.Height} px {rule}");
        }
    }

    /// <summary>The options given on the command line that set part of the job (a run repeated from its log takes them all from the log).</summary>
    public IEnumerable<string> Given(ParseResult result) =>
        new Option[]
        {
            Mask.Threshold, Mask.Dither, Mask.Invert, WidthMm, HeightMm, PitchUm, ImageDpi, OriginMm, Strategy, Bidirectional, Unidirectional,
            OverscanMm, Profile, FrequencyHz, SpeedMmS, TravelSpeedMmS, AccelerationMmS2, Mode, PulsesPerDot, DotPitchMicrosteps, DotSettleMs,
        }.Where(option => OptionChecks.IsGiven(result, option)).Select(option => option.Name);

    /// <summary>The dot-mode options; refused with one line when out of range or given without <c>--mode dots</c>.</summary>
    private ProcessSettings BindDots(ParseResult result, ProcessSettings process)
    {
        var mode = ParseMode(result.GetValue(Mode));
        var pulses = result.GetValue(PulsesPerDot);
        var pitch = result.GetValue(DotPitchMicrosteps);
        var settle = result.GetValue(DotSettleMs);
        if (mode != PlanMode.Dots)
        {
            var stray = new Option[] { PulsesPerDot, DotPitchMicrosteps, DotSettleMs }.FirstOrDefault(o => OptionChecks.IsGiven(result, o));
            return stray is null ? process : throw new UsageException($"{stray.Name} applies to --mode dots only");
        }

        return process with { Mode = PlanMode.Dots, PulsesPerDot = pulses ?? 1, DotPitchMicrosteps = pitch ?? 0, DotSettleMs = settle ?? 0 };
    }

    internal static PlanMode ParseMode(string? text) => text?.Trim().ToLowerInvariant() switch
    {
        null or "" or "raster" => PlanMode.Raster,
        "dots" or "dot" => PlanMode.Dots,
        _ => throw new UsageException($"--mode {text}: use raster or dots"),
    };

    private SizeSpec BindSize(ParseResult result, string image, MachineLimits limits)
    {
        var width = result.GetValue(WidthMm);
        var height = result.GetValue(HeightMm);
        var pitch = result.GetValue(PitchUm);
        var dpi = result.GetValue(ImageDpi);
        var given = (width.HasValue || height.HasValue ? 1 : 0) + (pitch.HasValue ? 1 : 0) + (dpi ? 1 : 0);
        if (given == 0)
        {
            throw new UsageException("give the size: --width-mm, --height-mm, --pitch-um or --image-dpi");
        }

        if (given > 1)
        {
            throw new UsageException("give the size one way only: --width-mm/--height-mm, --pitch-um or --image-dpi");
        }

        // Each size given, before the image is read for its resolution.
        OptionChecks.Refuse(
            new JobSettings { SizeMode = SizeMode.WidthAndHeight, WidthMm = width ?? 1, HeightMm = height ?? 1 },
            limits,
            JobField.Width,
            JobField.Height);
        if (pitch is { } p)
        {
            OptionChecks.Refuse(new JobSettings { SizeMode = SizeMode.Pitch, PitchUm = p }, limits, JobField.Pitch);
        }

        if (dpi)
        {
            var info = ImageLoader.ReadInfo(image);
            return info.DpiX is { } x && x > 0
                ? SizeSpec.Resolution(x)
                : throw new UsageException($"{image}: the image states no resolution; give --width-mm, --height-mm or --pitch-um");
        }

        return (width, height, pitch) switch
        {
            ({ } w, { } h, _) => SizeSpec.WidthAndHeight(w, h),
            ({ } w, null, _) => SizeSpec.Width(w),
            (null, { } h, _) => SizeSpec.Height(h),
            _ => SizeSpec.Pitch(pitch!.Value),
        };
    }

    public PlanOptions BindPlan(ParseResult result, MachineLimits limits)
    {
        var strategy = result.GetValue(Strategy)?.Trim().ToLowerInvariant() switch
        {
            "paper" => PlanStrategy.Paper,
            "optimized" or "optimised" => PlanStrategy.Optimized,
            var other => throw new UsageException($"--strategy {other}: use paper or optimized"),
        };
        if (result.GetValue(Bidirectional) && result.GetValue(Unidirectional))
        {
            throw new UsageException("--bidirectional and --unidirectional contradict each other");
        }

        var overscan = result.GetValue(OverscanMm);
        OptionChecks.Refuse(new JobSettings { OverscanMm = overscan }, limits, JobField.Overscan);

        return new PlanOptions { Strategy = strategy, Bidirectional = !result.GetValue(Unidirectional), OverscanMm = overscan };
    }

    internal static OriginMm ParseOrigin(string? text)
    {
        if (string.IsNullOrWhiteSpace(text))
        {
            return Core.Geometry.OriginMm.Zero;
        }

        return NumberText.TryParsePair(text, out var x, out var y, out var problem)
            ? new OriginMm(x, y)
            : throw new UsageException($"--origin-mm {text}: {problem}");
    }
}

/// <summary>Threshold, dither and invert: how an image becomes a burn mask.</summary>
internal sealed class MaskOptionSet
{
    public Option<double?> Threshold { get; } = new("--threshold") { Description = "Luminance threshold in percent (default 50): darker pixels burn; dithering quantises at mid-grey instead" };

    public Option<string?> Dither { get; } = new("--dither") { Description = "none, floyd-steinberg, atkinson or bayer" };

    public Option<bool> Invert { get; } = new("--invert") { Description = "Burn the light pixels instead of the dark ones" };

    public Option<string?> Mode { get; } = new("--mode") { Description = "raster (burn while moving, the default) or dots (stop at each dot and fire a counted burst)" };

    public Option<int?> PulsesPerDot { get; } = new("--pulses-per-dot") { Description = "Pulses fired at each dot in --mode dots (default 1)" };

    public Option<long?> DotPitchMicrosteps { get; } = new("--dot-pitch-microsteps") { Description = "Distance between dots along a run, microsteps, in --mode dots (default: one dot at each pixel's centre)" };

    public Option<double?> DotSettleMs { get; } = new("--dot-settle-ms") { Description = "Time the stage is left to settle at each dot before the burst, ms (default 0)" };

    public void AddTo(Command command)
    {
        command.Options.Add(Threshold);
        command.Options.Add(Dither);
        command.Options.Add(Invert);
    }

    public MaskOptions Bind(ParseResult result)
    {
        var threshold = result.GetValue(Threshold) ?? 50;
        if (JobRules.Threshold(threshold) is { } rule)
        {
            throw new UsageException($"--threshold {threshold.ToString(CultureInfo.InvariantCulture)}: {rule}");
        }

        return new MaskOptions { ThresholdPercent = threshold, Dither = ParseDither(result.GetValue(Dither)), Invert = result.GetValue(Invert) };
    }

    internal static DitherMethod ParseDither(string? text)
    {
        var method = DitherNames.Parse(text, out var unknown);
        return unknown ? throw new UsageException($"--dither {text}: use {DitherNames.List}") : method;
    }
}
