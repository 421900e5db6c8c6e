using System.CommandLine;
using LaserEngrave.Core.Input;
using System.Globalization;
using LaserEngrave.Core.Alignment;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Cli.Commands;

/// <summary>`laserengrave align IMAGE --pitch-um P --mark JX,JY=SX,SY --mark ... --out ALIGNED.bmp`: turn a job to two marks found on the sample.</summary>
internal static class AlignCommand
{
    public static Command Create()
    {
        var image = new Argument<string>("IMAGE") { Description = "Image file of the job" };
        var mask = new MaskOptionSet();
        var pitch = new Option<double?>("--pitch-um") { Description = "Pixel pitch of the job, µm" };
        var width = new Option<double?>("--width-mm") { Description = "Width of the job, mm (instead of --pitch-um)" };
        var marks = new Option<string[]>("--mark")
        {
            Description = "A fiducial: its position in the job and the stage position where you found it, JX,JY=SX,SY in mm (give two)",
            Required = true,
        };
        var tolerance = new Option<double>("--tolerance-um")
        {
            Description = "Largest accepted difference between the marks' distance on the stage and in the job, µm",
            DefaultValueFactory = _ => FiducialAlignment.DefaultToleranceUm,
        };
        var profile = new Option<string?>("--profile") { Description = "Machine profile (JSON); its calibration, if any, is applied to the stage positions" };
        var output = new Option<string>("--out") { Description = "Aligned mask to write: .bmp or .png (black = burn)", Required = true };
        var json = new Option<bool>("--json") { Description = "Print one JSON object" };
        var command = new Command("align", "Rotate and move a job onto two fiducial marks found on the sample; rows stay along the stage's X axis") { image };
        mask.AddTo(command);
        foreach (var option in new Option[] { pitch, width, marks, tolerance, profile, output, json })
        {
            command.Options.Add(option);
        }

        command.SetAction(result =>
        {
            var machine = result.GetValue(profile) is { } path ? MachineProfile.Load(path) : MachineProfile.Default;
            var fiducials = (result.GetValue(marks) ?? []).Select(ParseMark).ToArray();
            if (fiducials.Length != 2)
            {
                throw new UsageException($"give exactly two --mark JX,JY=SX,SY (got {fiducials.Length})");
            }

            OptionChecks.OutputFile(result.GetValue(output), "--out");
            var bits = MaskBuilder.FromFile(result.GetValue(image)!, mask.Bind(result), out _);
            var pitchUm = (result.GetValue(pitch), result.GetValue(width)) switch
            {
                ({ } given, null) when given > 0 && double.IsFinite(given) => given,
                (null, { } w) when w > 0 && double.IsFinite(w) => Units.MmToUm(w) / bits.Width,
                (null, null) => throw new UsageException("give the job's size: --pitch-um or --width-mm"),
                ({ }, { }) => throw new UsageException("give --pitch-um or --width-mm, not both"),
                _ => throw new UsageException("--pitch-um and --width-mm must be above 0"),
            };
            var target = result.GetValue(output)!;
            var bmp = target.EndsWith(".bmp", StringComparison.OrdinalIgnoreCase);
            if (!bmp && !target.EndsWith(".png", StringComparison.OrdinalIgnoreCase))
            {
                throw new UsageException($"--out {target}: give a .bmp or .png file");
            }

            FiducialAlignment alignment;
            AlignedMask aligned;
            try
            {
                alignment = FiducialAlignment.Solve(fiducials[0], fiducials[1], result.GetValue(tolerance), machine.Calibration);
                aligned = MaskResampler.Resample(bits, pitchUm, alignment.Transform, machine.Calibration);
            }
            catch (AlignmentException ex)
            {
                throw new UsageException(ex.Message);
            }

            if (bmp)
            {
                BmpMaskWriter.Write(target, aligned.Mask, pitchUm);
            }
            else
            {
                PngWriter.WriteMask(target, aligned.Mask);
            }

            var stdout = result.InvocationConfiguration.Output;
            var c = CultureInfo.InvariantCulture;
            if (result.GetValue(json))
            {
                CliJson.Write(stdout, new AlignSummary(
                    target,
                    alignment.Transform.AngleDegrees,
                    alignment.ScaleMismatchPpm,
                    alignment.DistanceMismatchUm,
                    alignment.ResidualUm,
                    pitchUm,
                    aligned.Mask.Width,
                    aligned.Mask.Height,
                    aligned.OriginXMm,
                    aligned.OriginYMm));
                return 0;
            }

            stdout.WriteLine(string.Create(c, $"Rotation:        {alignment.Transform.AngleDegrees:+0.####;-0.####;0}° (+x turned towards +y)"));
            stdout.WriteLine(string.Create(c, $"Distance check:  {alignment.DistanceMismatchUm:+0.#;-0.#;0} µm between the marks ({alignment.ScaleMismatchPpm:+0;-0;0} ppm), each mark {alignment.ResidualUm:0.#} µm from the fit"));
            stdout.WriteLine(string.Create(c, $"Aligned mask:    {target}, {aligned.Mask.Width} x {aligned.Mask.Height} px at {pitchUm:0.####} µm"));
            stdout.WriteLine(string.Create(c, $"New origin:      {aligned.OriginXMm:0.####},{aligned.OriginYMm:0.####} mm"));
            stdout.WriteLine(string.Create(c, $"Engrave it with: laserengrave engrave {target} --pitch-um {pitchUm:0.######} --origin-mm {aligned.OriginXMm:0.####},{aligned.OriginYMm:0.####}{(result.GetValue(profile) is { } p ? $" --profile {p}" : string.Empty)} ..."));
            return 0;
        });
        return command;
    }

    private static Fiducial ParseMark(string text)
    {
        var halves = text.Split('=');
        if (halves.Length != 2)
        {
            throw new UsageException($"--mark {text}: expected JX,JY=SX,SY in mm, e.g. 1,1=21.02,16.03 (or 1;1=21,02;16,03 with decimal commas)");
        }

        var (jx, jy) = Pair(halves[0], "the job's point");
        var (sx, sy) = Pair(halves[1], "the stage's point");
        return new Fiducial(jx, jy, sx, sy);

        (double X, double Y) Pair(string part, string what) =>
            NumberText.TryParsePair(part, out var x, out var y, out var problem)
                ? (x, y)
                : throw new UsageException($"--mark {text}: {what} '{part}' {problem}");
    }
}

/// <summary>`align --json`: the fit of the two marks and the aligned mask.</summary>
internal sealed record AlignSummary(
    string Output,
    double RotationDegrees,
    double ScaleMismatchPpm,
    double DistanceMismatchUm,
    double ResidualUm,
    double PitchUm,
    int WidthPx,
    int HeightPx,
    double OriginXMm,
    double OriginYMm);
