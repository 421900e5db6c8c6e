using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Jobs;

/// <summary>
/// The rules beyond a job's fields that the command line, the app's fields, the HTTP API and the devices all ask: a test
/// fire, a jog step, where a job may stand on the stage, and the process values alone (what the planners take).
/// </summary>
/// <remarks>Each returns the sentence that refuses a value (null when it is usable), so every front end says the same.</remarks>
public static partial class JobRules
{
    /// <summary>The most pulses one test fire may ask for: the laser gate's burst range, as for a dot.</summary>
    public const int MaxTestPulses = MaxPulsesPerDot;

    /// <summary>The longest test fire, ms.</summary>
    public const int MaxTestFireMs = 60_000;

    /// <summary>Null when <paramref name="pulses"/> is a test fire the gate takes as one burst.</summary>
    public static string? TestFirePulses(long pulses) =>
        pulses is >= 1 and <= MaxTestPulses ? null : $"must be 1..{MaxTestPulses} pulses (the laser gate's burst range)";

    /// <summary>Null when <paramref name="ms"/> is a test fire's length.</summary>
    public static string? TestFireMs(long ms) =>
        ms is >= 1 and <= MaxTestFireMs ? null : $"must be 1..{MaxTestFireMs} ms";

    /// <summary>Null when a jog of <paramref name="stepUm"/> (signed) along an axis of <paramref name="travelMm"/> is a step the stage can make.</summary>
    /// <remarks>The travel, not a fixed number: a 150 mm stage jogs 100 mm, a 25 mm one does not; the stage refuses a target off the axis when the jog is made.</remarks>
    public static string? JogStep(double stepUm, double travelMm, string axis)
    {
        var travelUm = Units.MmToUm(travelMm);
        return !double.IsFinite(stepUm) || stepUm == 0 ? "must be a finite number other than 0"
            : Math.Abs(stepUm) > travelUm ? $"longer than the {axis} travel ({N(travelUm)} µm)"
            : null;
    }

    /// <summary>Null when a pulse energy is not known (null) or a finite energy above 0.</summary>
    public static string? PulseEnergy(double? uj) =>
        uj is not { } energy || (energy > 0 && double.IsFinite(energy)) ? null : "must be a finite number above 0 (or left out: not known)";

    /// <summary>Null when a dot pitch is 0 (one dot at each pixel's centre) or a whole number of microsteps within the travel.</summary>
    public static string? DotPitch(long microsteps, MachineLimits limits)
    {
        ArgumentNullException.ThrowIfNull(limits);
        var travel = Math.Min(limits.TravelXMicrosteps, limits.TravelYMicrosteps);
        return microsteps >= 0 && microsteps <= travel ? null : $"must be 0 (one dot at each pixel's centre) to {travel} (the travel)";
    }

    /// <summary>Null when a settle time at each dot is one the run waits.</summary>
    public static string? DotSettle(double ms) => ms is >= 0 and <= MaxDotSettleMs ? null : $"must be 0..{N(MaxDotSettleMs)} ms";

    /// <summary>
    /// Null when the job, as planned, stays inside the stage's travel: an image's pixel grid, a drawing's paths with its
    /// strokes' run-ups and run-outs. Otherwise the one sentence that refuses it, whether it was typed, dropped on the stage
    /// or started: the command line, the app's origin field, its stage and Start, and the engine's preflight all say it.
    /// </summary>
    public static string? Placement(PreparedJob job)
    {
        ArgumentNullException.ThrowIfNull(job);
        var g = job.Geometry;
        return g.FitsTravel ? null : OutsideTravel("job", g.AchievedWidthMm, g.AchievedHeightMm, job.Spec, string.Empty);
    }

    /// <inheritdoc cref="Placement(PreparedJob)"/>
    public static string? Placement(PreparedDrawing drawing)
    {
        ArgumentNullException.ThrowIfNull(drawing);
        return drawing.FitsTravel ? null : OutsideTravel("drawing", drawing.Plan.WidthMm, drawing.Plan.HeightMm, drawing.Spec, ", with its strokes' run-ups and run-outs");
    }

    /// <summary>
    /// Every process value the rules refuse, in the order of the fields: what the planners take, checked by the same rules
    /// as a job's fields (<see cref="Check(JobSettings, MachineLimits)"/>), plus what only a process carries (its mode, the baud rates).
    /// </summary>
    public static IReadOnlyList<FieldProblem> Check(ProcessSettings process, MachineLimits limits)
    {
        ArgumentNullException.ThrowIfNull(process);
        ArgumentNullException.ThrowIfNull(limits);
        var problems = new List<FieldProblem>();
        void Add(string field, double value, string? rule)
        {
            if (rule is not null)
            {
                problems.Add(new FieldProblem(field, value, rule));
            }
        }

        Add(JobField.Frequency, process.LaserFrequencyHz, Frequency(process.LaserFrequencyHz, limits));
        Add(JobField.BurnSpeed, process.BurnSpeedMmPerS, Speed(process.BurnSpeedMmPerS, limits));
        Add(JobField.TravelSpeed, process.TravelSpeedMmPerS, Speed(process.TravelSpeedMmPerS, limits));
        Add(JobField.Acceleration, process.AccelerationMmPerS2, Acceleration(process.AccelerationMmPerS2, limits));
        if (process.PulseEnergyUj is { } energy)
        {
            Add(JobField.PulseEnergy, energy, PulseEnergy(energy));
        }

        // A raster job carries 1 pulse, pitch 0 and no settle; the values are checked in either mode, as a log keeps them.
        Add(JobField.PulsesPerDot, process.PulsesPerDot, PulsesPerDot(process.PulsesPerDot));
        Add(JobField.DotPitch, process.DotPitchMicrosteps, DotPitch(process.DotPitchMicrosteps, limits));
        Add(JobField.DotSettle, process.DotSettleMs, DotSettle(process.DotSettleMs));
        Add(JobField.Mode, (int)process.Mode, Enum.IsDefined(process.Mode) ? null : "is not a mode: raster or dots");
        Add(JobField.StageBaud, process.StageBaudRate, process.StageBaudRate > 0 ? null : "must be above 0");
        Add(JobField.GateBaud, process.GateBaudRate, process.GateBaudRate > 0 ? null : "must be above 0");
        return problems;
    }

    /// <summary>Throws a <see cref="PlanException"/> with the first of <see cref="Check(ProcessSettings, MachineLimits)"/>'s problems.</summary>
    /// <remarks>Where a process is planned without its fields behind it (a job built in code, a log repeated): the same rules, one line.</remarks>
    public static void Require(ProcessSettings process, MachineProfile profile)
    {
        ArgumentNullException.ThrowIfNull(profile);
        if (Check(process, MachineLimits.Of(profile)) is [var first, ..])
        {
            throw new PlanException(first.Message);
        }
    }

    /// <summary>The one sentence for a job, drawing or layer (<paramref name="what"/>) that leaves the stage's travel: the
    /// origin field, a drop on the stage, Start and the command line all say it.</summary>
    public static string OutsideTravel(string what, double widthMm, double heightMm, JobSpec spec, string with = "") =>
        $"the {what} ({N(Math.Round(widthMm, 3))} x {N(Math.Round(heightMm, 3))} mm at origin {N(Math.Round(spec.Origin.X, 3))}, {N(Math.Round(spec.Origin.Y, 3))} mm{with}) "
        + $"does not fit the stage's travel ({N(spec.Profile.X.TravelMm)} x {N(spec.Profile.Y.TravelMm)} mm): move the origin or make it smaller";
}
