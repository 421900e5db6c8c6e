using System.CommandLine;
using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;

namespace LaserEngrave.Cli.Commands;

/// <summary>Range checks for numbers on the command line, each refusing with one line naming the option and the allowed range.</summary>
internal static class OptionChecks
{
    /// <summary>Whether <paramref name="option"/> was typed on the command line (not just its default).</summary>
    public static bool IsGiven(ParseResult result, Option option) => result.GetResult(option) is { Implicit: false };

    /// <summary>The fields the process options set (speeds, acceleration, frequency and the dot values).</summary>
    public static readonly string[] ProcessFields =
    [
        JobField.Frequency, JobField.BurnSpeed, JobField.TravelSpeed, JobField.Acceleration, JobField.PulseEnergy,
        JobField.PulsesPerDot, JobField.DotPitch, JobField.DotSettle,
    ];

    /// <summary>
    /// Refuses the first value the job rules (<see cref="JobRules.Check(JobSettings, MachineLimits)"/>, the app's and the
    /// files' too) refuse, naming its option; only <paramref name="fields"/> are asked when given.
    /// </summary>
    public static void Refuse(JobSettings settings, MachineLimits limits, params string[] fields)
    {
        var problem = JobRules.Check(settings, limits).FirstOrDefault(p => fields.Length == 0 || fields.Contains(p.Field));
        if (problem is not null)
        {
            throw new UsageException(Describe(problem));
        }
    }

    /// <summary>A job rule's problem in the command line's words: the option and the value as typed.</summary>
    public static string Describe(FieldProblem problem) => problem.Field switch
    {
        JobField.OriginX => $"--origin-mm: X {problem.ValueText} mm is {problem.Rule}",
        JobField.OriginY => $"--origin-mm: Y {problem.ValueText} mm is {problem.Rule}",
        _ => problem.MessageFor(OptionName(problem.Field)),
    };

    /// <summary>The option that sets a job field.</summary>
    public static string OptionName(string field) => field switch
    {
        JobField.Threshold => "--threshold",
        JobField.Width => "--width-mm",
        JobField.Height => "--height-mm",
        JobField.Pitch => "--pitch-um",
        JobField.Frequency => "--frequency-hz",
        JobField.BurnSpeed => "--speed-mm-s",
        JobField.TravelSpeed => "--travel-speed-mm-s",
        JobField.Acceleration => "--acceleration-mm-s2",
        JobField.Overscan => "--overscan-mm",
        JobField.Passes => "--passes",
        JobField.PulsesPerDot => "--pulses-per-dot",
        JobField.DotPitch => "--dot-pitch-microsteps",
        JobField.DotSettle => "--dot-settle-ms",
        JobField.Tolerance => "--tolerance-um",
        JobField.FillPitch => "--fill-pitch-um",
        _ => field,
    };

    /// <summary>Refuses a position outside 0..<paramref name="travelMm"/>, NaN included.</summary>
    public static void WithinTravel(double mm, double travelMm, string name, string axis)
    {
        if (!(mm >= 0 && mm <= travelMm))
        {
            throw new UsageException($"{name}: {axis} {N(mm)} mm is outside the travel 0..{N(travelMm)} mm");
        }
    }

    /// <summary>Refuses a value above <paramref name="max"/>; <paramref name="what"/> is the unit and what the maximum is.</summary>
    public static void AtMost(double? value, double max, string name, string what)
    {
        if (value is { } v && v > max)
        {
            throw new UsageException($"{name} {N(v)}: at most {N(max)} {what}");
        }
    }

    /// <summary>Refuses a whole number outside <paramref name="min"/>..<paramref name="max"/>; <paramref name="why"/> says where the bound comes from.</summary>
    public static void InRange(long? value, long min, long max, string name, string unit, string why)
    {
        if (value is { } v && (v < min || v > max))
        {
            throw new UsageException($"{name} {v}: must be {min}..{max}{unit} ({why})");
        }
    }

    /// <summary>Refuses an output path that exists but is not a regular file (writing to a named pipe would block until something reads it), or whose folder does not exist.</summary>
    public static void OutputFile(string? path, string name)
    {
        if (path is null)
        {
            return;
        }

        if (path.Length == 0)
        {
            throw new UsageException($"{name}: give a file name");
        }

        if (Core.IO.RegularFile.Problem(path) is { } problem)
        {
            throw new UsageException($"{name} {path}: {problem}");
        }

        // Found now, not when the file is written after minutes of work (or left half written).
        var folder = Path.GetDirectoryName(Path.GetFullPath(path));
        if (folder is not null && !Directory.Exists(folder))
        {
            throw new UsageException($"{name} {path}: the folder {folder} does not exist{(File.Exists(folder) ? " (it is a file)" : string.Empty)}");
        }
    }

    /// <summary>A number as messages show it: invariant, short, exponent form when huge or tiny.</summary>
    public static string N(double value) =>
        value != 0 && double.IsFinite(value) && (Math.Abs(value) >= 1e9 || Math.Abs(value) < 1e-5)
            ? value.ToString("G6", CultureInfo.InvariantCulture)
            : value.ToString("0.#####", CultureInfo.InvariantCulture);
}
