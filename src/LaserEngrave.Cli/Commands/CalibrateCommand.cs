using System.CommandLine;
using LaserEngrave.Core.Input;
using System.Globalization;
using LaserEngrave.Core.Calibration;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Cli.Commands;

/// <summary>`laserengrave calibrate pattern|solve|show|clear`: squareness and scale of the stage (seed 002), kept in the machine profile.</summary>
internal static class CalibrateCommand
{
    public static Command Create()
    {
        var command = new Command("calibrate", "Calibrate the stage's squareness and axis scales: write the pattern, solve from measurements, show or clear the result");
        command.Subcommands.Add(Pattern());
        command.Subcommands.Add(Solve());
        command.Subcommands.Add(Show());
        command.Subcommands.Add(Clear());
        return command;
    }

    private sealed class PatternOptions
    {
        public Option<double> SizeMm { get; } = new("--size-mm") { Description = "Side of the square pattern, mm", DefaultValueFactory = _ => 20 };

        public Option<double> PitchUm { get; } = new("--pitch-um") { Description = "Pixel pitch the pattern is engraved at, µm", DefaultValueFactory = _ => 10 };

        public Option<double> LineUm { get; } = new("--line-um") { Description = "Width of every line, µm", DefaultValueFactory = _ => 20 };

        public Option<double?> MarkSpacingMm { get; } = new("--mark-spacing-mm") { Description = "Distance between scale marks, mm (default a tenth of the size)" };

        public void AddTo(Command command)
        {
            command.Options.Add(SizeMm);
            command.Options.Add(PitchUm);
            command.Options.Add(LineUm);
            command.Options.Add(MarkSpacingMm);
        }

        public CalibrationPattern Bind(ParseResult result) => Guard(() => CalibrationPattern.Create(
            result.GetValue(SizeMm), result.GetValue(PitchUm), result.GetValue(LineUm), result.GetValue(MarkSpacingMm)));
    }

    private static Command Pattern()
    {
        var options = new PatternOptions();
        var output = new Option<string?>("--out") { Description = "Mask to write: .png or .bmp (black = burn)" };
        var segments = new Option<string?>("--segments") { Description = "Also plan the pattern and write every move as CSV (microsteps)" };
        var origin = new Option<string?>("--origin-mm") { Description = "With --segments: stage position of the pattern's top-left corner, X,Y mm" };
        var profile = new Option<string?>("--profile") { Description = "With --segments: machine profile (its calibration, if any, compensates the plan)" };
        var command = new Command("pattern", "Write the calibration pattern (two grooves with scale marks, and a square) and list what to measure");
        options.AddTo(command);
        command.Options.Add(output);
        command.Options.Add(segments);
        command.Options.Add(origin);
        command.Options.Add(profile);
        command.SetAction(result =>
        {
            var pattern = options.Bind(result);
            var path = result.GetValue(output);
            OptionChecks.OutputFile(path, "--out");
            var csv = result.GetValue(segments);
            OptionChecks.OutputFile(csv, "--segments");
            if (path is null && csv is null)
            {
                throw new UsageException("give --out PATTERN.png (or .bmp) and/or --segments MOVES.csv");
            }

            var mask = pattern.ToMask();
            var stdout = result.InvocationConfiguration.Output;
            if (path is not null)
            {
                if (path.EndsWith(".bmp", StringComparison.OrdinalIgnoreCase))
                {
                    BmpMaskWriter.Write(path, mask, pattern.PitchUm);
                }
                else if (path.EndsWith(".png", StringComparison.OrdinalIgnoreCase))
                {
                    PngWriter.WriteMask(path, mask);
                }
                else
                {
                    throw new UsageException($"--out {path}: give a .png or .bmp file");
                }

                stdout.WriteLine(string.Create(CultureInfo.InvariantCulture, $"{path}: engrave it at --pitch-um {pattern.PitchUm:0.####} (e.g. laserengrave engrave {path} --pitch-um {pattern.PitchUm:0.####} --origin-mm X,Y ...)"));
            }

            if (csv is not null)
            {
                var machine = result.GetValue(profile) is { } p ? MachineProfile.Load(p) : MachineProfile.Default;
                var report = GeometryResolver.Resolve(SizeSpec.Pitch(pattern.PitchUm), mask.Width, mask.Height, JobOptions.ParseOrigin(result.GetValue(origin)), machine);
                MoveCsvWriter.Write(new RasterPlan(mask, report.Geometry), csv);
                stdout.WriteLine($"{csv}: the pattern's moves{(machine.Calibration is null ? string.Empty : ", compensated by the profile's calibration")}");
            }

            foreach (var line in pattern.Describe())
            {
                stdout.WriteLine(line);
            }

            return 0;
        });
        return command;
    }

    private static Command Solve()
    {
        var options = new PatternOptions();
        var profile = new Option<string>("--profile") { Description = "Machine profile (JSON) to store the calibration in; created from the default when missing", Required = true };
        var x = new Option<string[]>("--x") { Description = "A distance along the X groove: NOMINAL_MM=MEASURED_MM (repeat)" };
        var y = new Option<string[]>("--y") { Description = "A distance along the Y groove: NOMINAL_MM=MEASURED_MM (repeat)" };
        var sideX = new Option<double[]>("--side-x") { Description = "A measured side of the square along X (AB, DC), mm (repeat)" };
        var sideY = new Option<double[]>("--side-y") { Description = "A measured side of the square along Y (AD, BC), mm (repeat)" };
        var ac = new Option<double?>("--diagonal-ac") { Description = "Measured diagonal through the marked corner A, mm" };
        var bd = new Option<double?>("--diagonal-bd") { Description = "Measured diagonal from B to D, mm" };
        var angle = new Option<double?>("--angle-deg") { Description = "Measured angle between the X groove (to +X) and the Y groove (to +Y), degrees" };
        var sigmaUm = new Option<double>("--sigma-um") { Description = "Uncertainty of one length measurement, µm", DefaultValueFactory = _ => 1 };
        var sigmaDeg = new Option<double>("--sigma-deg") { Description = "Uncertainty of the angle measurement, degrees", DefaultValueFactory = _ => 0.01 };
        var note = new Option<string?>("--note") { Description = "A note stored with the calibration (sample, microscope, who)" };
        var replace = new Option<bool>("--replace") { Description = "The pattern was engraved without the profile's calibration: replace it instead of refining it" };
        var dryRun = new Option<bool>("--dry-run") { Description = "Solve and print, but do not write the profile" };
        var json = new Option<bool>("--json") { Description = "Print one JSON object" };
        var command = new Command("solve", "Solve squareness and axis scales from measurements of the engraved pattern and store them in the profile");
        options.AddTo(command);
        foreach (var option in new Option[] { profile, x, y, sideX, sideY, ac, bd, angle, sigmaUm, sigmaDeg, note, replace, dryRun, json })
        {
            command.Options.Add(option);
        }

        command.SetAction(result =>
        {
            var path = result.GetValue(profile)!;
            var existing = File.Exists(path) ? MachineProfile.Load(path) : MachineProfile.Default;
            var pattern = options.Bind(result);
            var measurements = new CalibrationMeasurements
            {
                X = ParseDistances(result.GetValue(x), "--x"),
                Y = ParseDistances(result.GetValue(y), "--y"),
                SquareSideMm = pattern.SquareSideMm,
                SquareSidesXMm = result.GetValue(sideX) ?? [],
                SquareSidesYMm = result.GetValue(sideY) ?? [],
                DiagonalAcMm = result.GetValue(ac),
                DiagonalBdMm = result.GetValue(bd),
                GrooveAngleDegrees = result.GetValue(angle),
                LengthUncertaintyUm = result.GetValue(sigmaUm),
                AngleUncertaintyDegrees = result.GetValue(sigmaDeg),
            };
            var solution = Guard(() => CalibrationSolver.Solve(measurements));
            var previous = result.GetValue(replace) ? null : existing.Calibration;
            var solved = solution.Calibration;
            var stored = (previous is null ? solved : previous.ThenResidual(solved)) with
            {
                SquarenessUncertaintyDegrees = solved.SquarenessUncertaintyDegrees,
                ScaleXUncertaintyPpm = solved.ScaleXUncertaintyPpm,
                ScaleYUncertaintyPpm = solved.ScaleYUncertaintyPpm,
                Date = TimeProvider.System.GetUtcNow(),
                Note = result.GetValue(note),
            };
            Guard(() => stored.Validate());
            var written = !result.GetValue(dryRun);
            if (written)
            {
                (existing with { Calibration = stored }).Save(path);
            }

            var stdout = result.InvocationConfiguration.Output;
            if (result.GetValue(json))
            {
                CliJson.Write(stdout, new CalibrationSolveSummary(
                    path,
                    written,
                    previous is not null,
                    solved,
                    stored,
                    solution.DegreesOfFreedom,
                    solution.LengthRmsUm,
                    solution.NormalizedRms,
                    solution.Residuals));
                return 0;
            }

            var c = CultureInfo.InvariantCulture;
            stdout.WriteLine(string.Create(c, $"Measured errors:  {solved.Describe()}"));
            stdout.WriteLine(string.Create(c, $"Uncertainty (1σ): ±{solved.SquarenessUncertaintyDegrees:0.#####}°, X ±{solved.ScaleXUncertaintyPpm:0.#} ppm, Y ±{solved.ScaleYUncertaintyPpm:0.#} ppm ({measurements.Count} measurements, ±{measurements.LengthUncertaintyUm:0.###} µm, ±{measurements.AngleUncertaintyDegrees:0.####}° each)"));
            stdout.WriteLine(string.Create(c, $"Residuals:        {solution.DegreesOfFreedom} degrees of freedom, length rms {solution.LengthRmsUm:0.###} µm{(solution.NormalizedRms is { } n ? $", {n:0.##} x the stated uncertainty" : " (exactly determined)")}"));
            foreach (var r in solution.Residuals)
            {
                stdout.WriteLine(string.Create(c, $"  {r.Name,-18} measured {r.Measured:0.#####} {r.Unit}, model {r.Predicted:0.#####} {r.Unit}, residual {r.Residual:+0.###;-0.###;0} {(r.Unit == "°" ? "°" : "µm")}"));
            }

            if (previous is not null)
            {
                stdout.WriteLine($"Refined:          the pattern was engraved with {previous.Describe()} compensating (--replace if it was not)");
            }

            stdout.WriteLine(string.Create(c, $"Calibration:      {stored.Describe()}{(written ? $" -> {path}" : " (dry run: not written)")}"));
            if (solution.NormalizedRms is > 3)
            {
                result.InvocationConfiguration.Error.WriteLine("warning: the measurements disagree with each other far more than the stated uncertainty; check the largest residual");
            }

            return 0;
        });
        return command;
    }

    private static Command Show()
    {
        var profile = new Option<string>("--profile") { Description = "Machine profile (JSON)", Required = true };
        var json = new Option<bool>("--json") { Description = "Print the calibration as JSON (null when uncalibrated)" };
        var command = new Command("show", "Print the profile's calibration") { profile, json };
        command.SetAction(result =>
        {
            var loaded = MachineProfile.Load(result.GetValue(profile)!);
            var stdout = result.InvocationConfiguration.Output;
            if (result.GetValue(json))
            {
                CliJson.Write(stdout, new CalibrationShowSummary(result.GetValue(profile), loaded.Calibration));
                return 0;
            }

            if (loaded.Calibration is not { } c)
            {
                stdout.WriteLine($"{result.GetValue(profile)}: not calibrated (square and true to scale assumed)");
                return 0;
            }

            stdout.WriteLine($"{result.GetValue(profile)}: {c.Describe()}");
            stdout.WriteLine(string.Create(CultureInfo.InvariantCulture, $"Solved:      {c.Date:yyyy-MM-dd HH:mm} UTC, ±{c.SquarenessUncertaintyDegrees:0.#####}°, X ±{c.ScaleXUncertaintyPpm:0.#} ppm, Y ±{c.ScaleYUncertaintyPpm:0.#} ppm"));
            if (c.Note is not null)
            {
                stdout.WriteLine($"Note:        {c.Note}");
            }

            return 0;
        });
        return command;
    }

    private static Command Clear()
    {
        var profile = new Option<string>("--profile") { Description = "Machine profile (JSON)", Required = true };
        var command = new Command("clear", "Remove the calibration from the profile: later jobs are not compensated") { profile };
        command.SetAction(result =>
        {
            var path = result.GetValue(profile)!;
            var loaded = MachineProfile.Load(path);
            if (loaded.Calibration is null)
            {
                result.InvocationConfiguration.Output.WriteLine($"{path}: not calibrated; nothing to clear");
                return 0;
            }

            (loaded with { Calibration = null }).Save(path);
            result.InvocationConfiguration.Output.WriteLine($"{path}: calibration removed (was {loaded.Calibration.Describe()})");
            return 0;
        });
        return command;
    }

    private static ScaleMeasurement[] ParseDistances(string[]? values, string option) =>
        [.. (values ?? []).Select(text =>
        {
            var parts = text.Split('=');
            if (parts.Length != 2)
            {
                throw new UsageException($"{option} {text}: expected NOMINAL_MM=MEASURED_MM, e.g. 16=16.0080 or 16=16,0080");
            }

            return NumberText.TryParse(parts[0], out var nominal, out var nominalProblem)
                ? NumberText.TryParse(parts[1], out var measured, out var measuredProblem)
                    ? new ScaleMeasurement(nominal, measured)
                    : throw new UsageException($"{option} {text}: the measured {parts[1].Trim()} {measuredProblem}")
                : throw new UsageException($"{option} {text}: the nominal {parts[0].Trim()} {nominalProblem}");
        })];

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

    private static void Guard(Action action) => Guard(() =>
    {
        action();
        return 0;
    });
}

/// <summary>`calibrate solve --json`: what the measurements gave, what was stored, and the residuals.</summary>
internal sealed record CalibrationSolveSummary(
    string Profile,
    bool Written,
    bool Refined,
    AxisCalibration Measured,
    AxisCalibration Calibration,
    int DegreesOfFreedom,
    double LengthRmsUm,
    double? NormalizedRms,
    IReadOnlyList<MeasurementResidual> Residuals);

/// <summary>`calibrate show --json`: the profile's calibration, null when uncalibrated.</summary>
internal sealed record CalibrationShowSummary(string? Profile, AxisCalibration? Calibration);
