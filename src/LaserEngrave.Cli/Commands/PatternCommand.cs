using System.CommandLine;
using System.Globalization;
using LaserEngrave.Core.Calibration;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Cli.Commands;

/// <summary>`laserengrave pattern scan-offset`: test patterns for the machine's settings; the bidirectional scan offset first.</summary>
internal static class PatternCommand
{
    /// <summary>Space between the blocks of two speeds, mm.</summary>
    internal const double BlockSpacingMm = 0.5;

    public static Command Create()
    {
        var command = new Command("pattern", "Write test patterns for the machine's settings");
        command.Subcommands.Add(ScanOffset());
        return command;
    }

    private static Command ScanOffset()
    {
        var output = new Option<string>("--out") { Description = "Mask to write: .png or .bmp (black = burn)", Required = true };
        var pitch = new Option<double>("--pitch-um") { Description = "Pixel pitch, µm; above the spot, so that rows burn as separate lines", DefaultValueFactory = _ => 25 };
        var barWidth = new Option<double>("--bar-width-um") { Description = "Width of every bar, µm", DefaultValueFactory = _ => 200 };
        var barHeight = new Option<double>("--bar-height-um") { Description = "Height of every bar, µm (an even number of rows)", DefaultValueFactory = _ => 500 };
        var bars = new Option<int>("--bars") { Description = "Bars in a block", DefaultValueFactory = _ => 5 };
        var gap = new Option<double>("--gap-um") { Description = "Space between two bars, µm", DefaultValueFactory = _ => 300 };
        var speeds = new Option<double[]>("--speed-mm-s") { Description = "A burn speed to test, mm/s (repeat for a block per speed; default: the profile's burn speed)" };
        var origin = new Option<string?>("--origin-mm") { Description = "Stage position of the first block's top-left corner, X,Y mm; each further speed's block goes below", DefaultValueFactory = _ => "10,10" };
        var profile = new Option<string?>("--profile") { Description = "Machine profile (JSON): speed limits, acceleration, and the scan offsets the engraving will apply" };
        var command = new Command("scan-offset", "Write the bidirectional scan offset pattern (short vertical bars, rows burned in alternate directions) and the engrave command for each speed")
        {
            output, pitch, barWidth, barHeight, bars, gap, speeds, origin, profile,
        };
        command.SetAction(result =>
        {
            var path = result.GetValue(output)!;
            var bmp = path.EndsWith(".bmp", StringComparison.OrdinalIgnoreCase);
            if (!bmp && !path.EndsWith(".png", StringComparison.OrdinalIgnoreCase))
            {
                throw new UsageException($"--out {path}: give a .png or .bmp file");
            }

            OptionChecks.OutputFile(path, "--out");
            var machine = result.GetValue(profile) is { } p ? MachineProfile.Load(p) : MachineProfile.Default;
            var pattern = Guard(() => ScanOffsetPattern.Create(result.GetValue(pitch), result.GetValue(barWidth), result.GetValue(barHeight), result.GetValue(bars), result.GetValue(gap)));
            var tested = Speeds(result.GetValue(speeds), machine);
            var start = JobOptions.ParseOrigin(result.GetValue(origin));
            var limits = MachineLimits.Of(machine);
            var lastY = start.Y + ((tested.Count - 1) * (pattern.HeightMm + BlockSpacingMm));
            OptionChecks.WithinTravel(start.X, limits.TravelXMm, "--origin-mm", "X");
            OptionChecks.WithinTravel(start.Y, limits.TravelYMm, "--origin-mm", "Y");
            if (start.X + pattern.WidthMm > limits.TravelXMm || lastY + pattern.HeightMm > limits.TravelYMm)
            {
                throw new UsageException(string.Create(
                    CultureInfo.InvariantCulture,
                    $"--origin-mm {start.X:0.###},{start.Y:0.###}: {tested.Count} block(s) of {pattern.WidthMm:0.###} x {pattern.HeightMm:0.###} mm reach {start.X + pattern.WidthMm:0.###}, {lastY + pattern.HeightMm:0.###} mm, past the travel ({limits.TravelXMm:0.###} x {limits.TravelYMm:0.###} mm)"));
            }

            var mask = pattern.ToMask();
            if (bmp)
            {
                BmpMaskWriter.Write(path, mask, pattern.PitchUm);
            }
            else
            {
                PngWriter.WriteMask(path, mask);
            }

            var c = CultureInfo.InvariantCulture;
            var stdout = result.InvocationConfiguration.Output;
            stdout.WriteLine($"{path}: the scan offset pattern");
            foreach (var line in pattern.Describe())
            {
                stdout.WriteLine(line);
            }

            stdout.WriteLine(tested.Count == 1 ? "Engrave it at the speed to test:" : $"Engrave it once per speed, each block {BlockSpacingMm.ToString(c)} mm below the last:");
            var profileArgument = result.GetValue(profile) is { } given ? $" --profile {given}" : string.Empty;
            for (var k = 0; k < tested.Count; k++)
            {
                var speed = tested[k];

                // A run-up as long as the stage needs to reach the speed, so the bars' edges burn at it.
                var overscan = Math.Max(0.01, Math.Ceiling(speed * speed / (2 * machine.AccelerationMmPerS2) * 100) / 100);
                var y = start.Y + (k * (pattern.HeightMm + BlockSpacingMm));
                stdout.WriteLine(string.Create(c, $"  laserengrave engrave {path} --pitch-um {pattern.PitchUm:0.####} --origin-mm {start.X:0.####},{y:0.####} --speed-mm-s {speed:0.####} --bidirectional --overscan-mm {overscan:0.##}{profileArgument} --sample scan-offset-{speed:0.####}mm-s"));
            }

            stdout.WriteLine(string.Create(c, $"The engraving applies the profile's scan offsets: {string.Join(", ", tested.Select(s => string.Create(c, $"{machine.ScanOffsetUmAt(s):0.###} µm at {s:0.####} mm/s")))}."));
            stdout.WriteLine("Under the microscope, in each block: where the right-to-left rows (2nd, 4th, ...) lie d µm left of the left-to-right rows, add d to that speed's offset; right of them, subtract d. Then enter the table in the profile:");
            stdout.WriteLine(string.Create(c, $"  \"scanOffsets\": [ {string.Join(", ", tested.Select(s => string.Create(c, $"{{ \"speedMmPerS\": {s:0.####}, \"offsetUm\": {machine.ScanOffsetUmAt(s):0.###} }}")))} ]"));
            return 0;
        });
        return command;
    }

    /// <summary>The speeds to test, in increasing order, each once; each within what the stage takes.</summary>
    private static List<double> Speeds(double[]? given, MachineProfile profile)
    {
        var limits = MachineLimits.Of(profile);
        if (given is null || given.Length == 0)
        {
            return [profile.BurnSpeedMmPerS];
        }

        foreach (var speed in given)
        {
            if (!limits.SpeedAllowed(speed))
            {
                throw new UsageException($"--speed-mm-s {OptionChecks.N(speed)}: outside what the stage takes ({limits.SpeedRange})");
            }
        }

        if (given.Distinct().Count() != given.Length)
        {
            throw new UsageException($"--speed-mm-s {string.Join(", ", given.Select(OptionChecks.N))}: each speed once");
        }

        return [.. given.Order()];
    }

    private static T Guard<T>(Func<T> action)
    {
        try
        {
            return action();
        }
        catch (CalibrationException ex)
        {
            throw new UsageException(ex.Message);
        }
    }
}
