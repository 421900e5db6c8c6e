using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Process;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Jobs;

/// <summary>
/// The one set of rules a job's values meet before anything moves, whoever gives them: the command line's options, the
/// app's fields, a preset, a job file's layer, a sweep's cells and a run log repeated. Each front end only maps the
/// <see cref="FieldProblem"/>s to its own names.
/// </summary>
/// <remarks>
/// The machine's side of every range comes from <see cref="MachineLimits.Of"/>, the one place a profile's limits are read:
/// speeds and acceleration within what both axes take (the slower axis' maximum, one unit of Zaber speed data the least),
/// the frequency within the gate's, positions and sizes within the travel, a pixel no smaller than a microstep.
/// </remarks>
public static partial class JobRules
{
    /// <summary>The most pulses a dot may get: the laser gate's burst range.</summary>
    public const int MaxPulsesPerDot = 1_000_000;

    /// <summary>The longest settle time at a dot, ms.</summary>
    public const double MaxDotSettleMs = 60_000;

    /// <summary>Every value of <paramref name="settings"/> the rules refuse, in the order of the fields; empty when the job may be planned.</summary>
    /// <remarks>
    /// Only the values the job uses are checked: the size field its size mode reads (a drawing's width only when it is sized
    /// by width), the mask and overscan for images, the dot values in dot mode, tolerance and fill pitch for drawings.
    /// </remarks>
    public static IReadOnlyList<FieldProblem> Check(JobSettings settings, MachineLimits limits)
    {
        ArgumentNullException.ThrowIfNull(settings);
        ArgumentNullException.ThrowIfNull(limits);
        var problems = new List<FieldProblem>();
        void Add(string field, double value, string? rule)
        {
            if (rule is not null)
            {
                problems.Add(new FieldProblem(field, value, rule));
            }
        }

        var drawing = settings.ImagePath is { } path && DrawingReader.IsDrawing(path);
        if (!drawing)
        {
            Add(JobField.Threshold, settings.ThresholdPercent, Threshold(settings.ThresholdPercent));
        }

        var mode = settings.SizeMode;
        if (drawing ? mode == SizeMode.Width : mode is SizeMode.Width or SizeMode.WidthAndHeight)
        {
            Add(JobField.Width, settings.WidthMm, Length(settings.WidthMm, limits.TravelXMm, "the X travel"));
        }

        if (!drawing && mode is SizeMode.Height or SizeMode.WidthAndHeight)
        {
            Add(JobField.Height, settings.HeightMm, Length(settings.HeightMm, limits.TravelYMm, "the Y travel"));
        }

        if (!drawing && mode == SizeMode.Pitch)
        {
            Add(JobField.Pitch, settings.PitchUm, Pitch(settings.PitchUm, limits));
        }

        Add(JobField.OriginX, settings.OriginXMm, Position(settings.OriginXMm, limits.TravelXMm));
        Add(JobField.OriginY, settings.OriginYMm, Position(settings.OriginYMm, limits.TravelYMm));
        Add(JobField.Frequency, settings.LaserFrequencyHz, Frequency(settings.LaserFrequencyHz, limits));
        Add(JobField.BurnSpeed, settings.BurnSpeedMmPerS, Speed(settings.BurnSpeedMmPerS, limits));
        Add(JobField.TravelSpeed, settings.TravelSpeedMmPerS, Speed(settings.TravelSpeedMmPerS, limits));
        Add(JobField.Acceleration, settings.AccelerationMmPerS2, Acceleration(settings.AccelerationMmPerS2, limits));
        if (!drawing)
        {
            Add(JobField.Overscan, settings.OverscanMm, settings.OverscanMm >= 0 && settings.OverscanMm <= limits.TravelXMm ? null : $"must be 0..{N(limits.TravelXMm)} mm (the X travel)");
        }

        Add(JobField.Passes, settings.Passes, Passes(settings.Passes));
        if (settings.PulseEnergyUj is { } energy)
        {
            Add(JobField.PulseEnergy, energy, PulseEnergy(energy));
        }

        if (!drawing && settings.Mode == PlanMode.Dots)
        {
            Add(JobField.PulsesPerDot, settings.PulsesPerDot, PulsesPerDot(settings.PulsesPerDot));
            Add(JobField.DotPitch, settings.DotPitchMicrosteps, DotPitch(settings.DotPitchMicrosteps, limits));
            Add(JobField.DotSettle, settings.DotSettleMs, DotSettle(settings.DotSettleMs));
        }

        if (drawing)
        {
            Add(JobField.Tolerance, settings.ToleranceUm, VectorOptions.ToleranceAllowed(settings.ToleranceUm) ? null : VectorOptions.ToleranceRule);
            Add(JobField.FillPitch, settings.FillPitchUm, VectorOptions.FillPitchAllowed(settings.FillPitchUm) ? null : VectorOptions.FillPitchRule);
        }

        return problems;
    }

    /// <summary>
    /// What the planned job itself refuses, as a problem of the field to change: pixels smaller than a microstep (the size
    /// field), a pixel too short for the laser gate to switch (the burn speed), a burst too long for its watchdog (the
    /// pulses per dot), a burn speed this computer cannot hold with this gate (<see cref="SpeedHold"/>); null when it can be engraved.
    /// </summary>
    /// <remarks>The command line refuses the first before planning, the engine the others at preflight (<see cref="PreparedJob.EngraveProblem"/>): found here, nothing starts.</remarks>
    public static FieldProblem? Check(PreparedJob job)
    {
        ArgumentNullException.ThrowIfNull(job);
        var spec = job.Spec;
        if (ResolvedPitch(job.Geometry.PitchUm, MachineLimits.Of(spec.Profile)) is { } small)
        {
            var (field, value) = spec.Size switch
            {
                SizeSpec.ByWidth w => (JobField.Width, w.WidthMm),
                SizeSpec.ByHeight h => (JobField.Height, h.HeightMm),
                SizeSpec.ByWidthAndHeight b => (JobField.Width, b.WidthMm),
                _ => (JobField.Pitch, job.Geometry.PitchUm),
            };
            return new FieldProblem(field, value, small);
        }

        if (job.Dots is null && job.Plan.SwitchingProblem is null && PixelPulses(job.Pulses) is { } tooFew)
        {
            return new FieldProblem(JobField.Frequency, spec.Process.LaserFrequencyHz, tooFew);
        }

        if (job.EngraveProblem is { } problem)
        {
            return job.Dots is null ? new FieldProblem(JobField.BurnSpeed, spec.Process.BurnSpeedMmPerS, problem)
                : new FieldProblem(JobField.PulsesPerDot, spec.Process.PulsesPerDot, problem);
        }

        // What this computer can hold with this gate: a counting gate is taken to time its switch-ons, which preflight
        // asks it (CAPS?) and refuses then if it does not; a frequency-only gate never does.
        var speed = spec.Process.BurnSpeedMmPerS;
        return job.Plan.Timing is not null && SpeedHold.Rule(speed, spec.Profile, scheduled: spec.Profile.Gate.CountsBursts) is { } tooFast
            ? new FieldProblem(JobField.BurnSpeed, speed, tooFast)
            : null;
    }

    /// <summary>
    /// Null when every pixel of a raster burn gets at least one pulse: the pulses, one every v / f along the line, come no
    /// further apart than a pixel. Otherwise the sentence that refuses it, with a frequency and a speed that would work.
    /// </summary>
    /// <remarks>
    /// Below one pulse a pixel, whole pixels inside a burn run get no pulse at all and the burn cannot equal the mask (the
    /// QR code at 5 mm and 5 Hz left 173 pixels unburned), so such a job is refused before anything moves, not warned of.
    /// </remarks>
    public static string? PixelPulses(PulseFigures pulses)
    {
        ArgumentNullException.ThrowIfNull(pulses);
        if (pulses.PitchUm is not { } pitch || pulses.PulsesPerPixel is not { } perPixel || perPixel >= 1)
        {
            return null;
        }

        var frequency = Math.Ceiling(PulseArithmetic.FrequencyHz(pulses.SpeedMmPerS, pitch, pulses.PulsesPerDot) - 1e-9);
        var speed = PulseArithmetic.SpeedMmPerS(pitch, pulses.FrequencyHz, pulses.PulsesPerDot);
        return $"gives each {N(Math.Round(pitch, 2))} µm pixel only {perPixel.ToString("0.##", System.Globalization.CultureInfo.InvariantCulture)} pulses at the burn speed of {N(pulses.SpeedMmPerS)} mm/s, so some pixels would get none: "
            + $"give at least {N(frequency)} Hz, or a burn speed of at most {N(Math.Floor(speed * 1000) / 1000)} mm/s";
    }

    /// <summary>Null when the pitch a size gives (by width, height or resolution) is at least a microstep, the smallest step the stage makes.</summary>
    public static string? ResolvedPitch(double pitchUm, MachineLimits limits)
    {
        ArgumentNullException.ThrowIfNull(limits);
        return pitchUm >= limits.MicrostepUm ? null
            : $"gives pixels of {N(pitchUm)} µm, below one microstep ({N(limits.MicrostepUm)} µm), the smallest step the stage makes; make the job larger";
    }

    /// <summary>Null when <paramref name="percent"/> is a threshold (the command line's mask command asks it without a machine).</summary>
    public static string? Threshold(double percent) => percent is >= 0 and <= 100 ? null : "must be between 0 and 100";

    /// <summary>Null when <paramref name="passes"/> is a number of passes.</summary>
    public static string? Passes(int passes) => passes is >= 1 and <= JobSpec.MaxPasses ? null : $"must be 1..{JobSpec.MaxPasses} (burns of the plan over the same place)";

    /// <summary>Null when <paramref name="pulses"/> is a burst the gate fires.</summary>
    public static string? PulsesPerDot(long pulses) => pulses is >= 1 and <= MaxPulsesPerDot ? null : $"must be 1..{MaxPulsesPerDot}";

    public static string? Speed(double mmPerS, MachineLimits limits) =>
        limits.SpeedAllowed(mmPerS) ? null : $"outside what the stage takes, {limits.SpeedRange} (the profile's maxSpeedMmPerS)";

    public static string? Acceleration(double mmPerS2, MachineLimits limits) =>
        limits.AccelerationAllowed(mmPerS2) ? null : $"outside what the stage takes, {limits.AccelerationRange} (the profile's maxAccelerationMmPerS2)";

    /// <remarks>
    /// A fraction of a hertz is refused, not rounded: the gate is sent whole Hz, and a run logged at 0.5 Hz that fired at
    /// 1 Hz would not tell what it did.
    /// </remarks>
    public static string? Frequency(double hz, MachineLimits limits)
    {
        ArgumentNullException.ThrowIfNull(limits);
        return !limits.FrequencyAllowed(hz) ? $"outside what the laser gate takes, 1..{limits.MaxFrequencyHz} Hz (the profile's gate.maxFrequencyHz)"
            : !MachineLimits.WholeHz(hz) ? $"is not a whole number of Hz: the laser gate is sent whole Hz; give {N(Math.Max(1, Math.Round(hz, MidpointRounding.AwayFromZero)))}"
            : null;
    }

    /// <summary>Null when a pixel pitch is at least a microstep (the smallest step the stage makes) and at most the travel.</summary>
    public static string? Pitch(double pitchUm, MachineLimits limits)
    {
        ArgumentNullException.ThrowIfNull(limits);
        var most = Units.MmToUm(Math.Min(limits.TravelXMm, limits.TravelYMm));
        return !(pitchUm > 0 && double.IsFinite(pitchUm)) ? "must be a finite number above 0"
            : pitchUm > most ? $"at most {N(most)} µm, the travel"
            : pitchUm < limits.MicrostepUm ? $"below one microstep ({N(limits.MicrostepUm)} µm), the smallest step the stage makes"
            : null;
    }

    private static string? Length(double mm, double travelMm, string travel) =>
        !(mm > 0 && double.IsFinite(mm)) ? "must be a finite number above 0"
        : mm > travelMm ? $"at most {N(travelMm)} mm, {travel}"
        : null;

    /// <summary>Null when <paramref name="mm"/> is a position on an axis of <paramref name="travelMm"/>: a job's origin, a go-to target.</summary>
    public static string? Position(double mm, double travelMm) =>
        mm >= 0 && mm <= travelMm ? null : $"outside the travel 0..{N(travelMm)} mm";

    private static string N(double value) => MachineLimits.Text.N(value);
}
