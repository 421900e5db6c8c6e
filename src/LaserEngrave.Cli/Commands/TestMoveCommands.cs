using System.CommandLine;
using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Machines.Runs;

namespace LaserEngrave.Cli.Commands;

/// <summary>`laserengrave frame | jog | goto | fire`: the test moves a technician makes before a run; the laser is off at the end of each.</summary>
internal static class TestMoveCommands
{
    public static IEnumerable<Command> All()
    {
        yield return Frame();
        yield return Jog();
        yield return GoTo();
        yield return Fire();
    }

    private static Command Frame()
    {
        var job = new JobOptions();
        var vector = new VectorOptionSet();
        var machine = new MachineOptions();
        var visibleHz = new Option<int?>("--visible-hz") { Description = "Fire at this low frequency while tracing, to see the frame (default: laser off)" };
        var command = new Command("frame", "Trace the job's bounding rectangle on the stage, laser off (or at --visible-hz), and stop at its top-left corner");
        job.AddTo(command);
        vector.AddTo(command);
        machine.AddTo(command);
        command.Options.Add(visibleHz);
        command.SetAction(async (result, ct) =>
        {
            // One job whichever kind the file is: the same rule as a run refuses it, and the box it answers is what is traced.
            EngraveJob engraving = VectorCommands.IsDrawing(result, job) ? VectorCommands.Prepare(result, job, vector) : PreparedJob.Prepare(job.Bind(result));
            var spec = engraving.Spec;

            // The laser is on around the whole frame: only a low frequency, to see the outline without burning it.
            OptionChecks.InRange(result.GetValue(visibleHz), 1, spec.Profile.MaxFrameFrequencyHz, "--visible-hz", " Hz", "the profile's maxFrameFrequencyHz");
            if (result.GetValue(visibleHz) is not null)
            {
                machine.RefuseUnacceptedNoWatchdog(result, spec.Profile);
            }

            if (EngraveRun.Unrunnable(engraving) is { } unrunnable)
            {
                throw new UsageException(unrunnable);
            }

            var box = engraving.FrameBox ?? throw new UsageException($"{spec.ImagePath}: no path to frame");
            return await WithMovesAsync(result, machine, spec.Profile, spec.Process, async moves =>
                Describe(await moves.FrameAsync(box.Left, box.Top, box.Right, box.Bottom, result.GetValue(visibleHz), ct), spec.Profile));
        });
        return command;
    }

    private static Command Jog()
    {
        var axis = new Argument<string>("AXIS") { Description = "x or y" };
        var step = new Argument<double>("STEP_UM") { Description = "Signed step in µm, e.g. 100 or -50" };
        var (machine, profile) = (new MachineOptions(), ProfileOption());
        var command = new Command("jog", "Move one axis by a step, laser off") { axis, step, profile };
        machine.AddTo(command);
        command.SetAction(async (result, ct) =>
        {
            var name = result.GetRequiredValue(axis).Trim().ToLowerInvariant() switch
            {
                "x" => StageAxisName.X,
                "y" => StageAxisName.Y,
                var other => throw new UsageException($"AXIS {other}: use x or y"),
            };
            var stepUm = result.GetValue(step);
            var machineProfile = LoadProfile(result, profile);
            if (JobRules.JogStep(stepUm, (name == StageAxisName.X ? machineProfile.X : machineProfile.Y).TravelMm, name.ToString()) is { } rule)
            {
                throw new UsageException($"STEP_UM {OptionChecks.N(stepUm)}: {rule}");
            }

            return await WithMovesAsync(result, machine, machineProfile, null, async moves =>
                Describe(await moves.JogAsync(name, stepUm, ct), machineProfile));
        });
        return command;
    }

    private static Command GoTo()
    {
        var x = new Argument<double>("X_MM") { Description = "Stage X, mm" };
        var y = new Argument<double>("Y_MM") { Description = "Stage Y, mm" };
        var (machine, profile) = (new MachineOptions(), ProfileOption());
        var command = new Command("goto", "Move to a stage position in mm, laser off") { x, y, profile };
        machine.AddTo(command);
        command.SetAction(async (result, ct) =>
        {
            var machineProfile = LoadProfile(result, profile);
            var (xMm, yMm) = (result.GetValue(x), result.GetValue(y));
            WithinTravel(xMm, machineProfile.X.TravelMm, "X_MM");
            WithinTravel(yMm, machineProfile.Y.TravelMm, "Y_MM");
            return await WithMovesAsync(result, machine, machineProfile, null, async moves =>
                Describe(await moves.GoToAsync(xMm, yMm, ct), machineProfile));
        });
        return command;
    }

    private static Command Fire()
    {
        var pulses = new Option<int?>("--pulses") { Description = "Fire this many pulses (the gate's burst)" };
        var ms = new Option<int?>("--ms") { Description = "Fire for this many milliseconds" };
        var frequency = new Option<int?>("--frequency-hz") { Description = "Pulse frequency, Hz (default: the profile's)" };
        var (machine, profile) = (new MachineOptions(), ProfileOption());
        var command = new Command("fire", "Test fire at the current position: N pulses or T ms, then off") { pulses, ms, frequency, profile };
        machine.AddTo(command);
        command.SetAction(async (result, ct) =>
        {
            var (count, duration) = (result.GetValue(pulses), result.GetValue(ms));
            if (count.HasValue == duration.HasValue)
            {
                throw new UsageException("give one of --pulses N or --ms T");
            }

            // The job rules' ranges, as the app and the devices refuse them.
            if (count is { } asked && JobRules.TestFirePulses(asked) is { } pulsesRule)
            {
                throw new UsageException($"--pulses {asked}: {pulsesRule}");
            }

            if (duration is { } length && JobRules.TestFireMs(length) is { } msRule)
            {
                throw new UsageException($"--ms {length}: {msRule}");
            }

            var machineProfile = LoadProfile(result, profile);
            OptionChecks.InRange(result.GetValue(frequency), 1, machineProfile.Gate.MaxFrequencyHz, "--frequency-hz", " Hz", "the profile's gate.maxFrequencyHz");
            var hz = result.GetValue(frequency) ?? (int)Math.Round(machineProfile.LaserFrequencyHz, MidpointRounding.AwayFromZero);
            machine.RefuseUnacceptedNoWatchdog(result, machineProfile);

            return await WithMovesAsync(result, machine, machineProfile, null, async moves =>
            {
                if (count is { } n)
                {
                    await moves.FirePulsesAsync(n, hz, ct);
                    return string.Create(CultureInfo.InvariantCulture, $"fired {n} pulses at {hz} Hz; {LaserOffWords(machineProfile)}");
                }

                await moves.FireForAsync(TimeSpan.FromMilliseconds(duration!.Value), hz, ct);
                return string.Create(CultureInfo.InvariantCulture, $"fired for {duration} ms at {hz} Hz; {LaserOffWords(machineProfile)}");
            });
        });
        return command;
    }

    /// <summary>Refuses a target off the axis before any port opens.</summary>
    private static void WithinTravel(double mm, double travelMm, string name)
    {
        if (JobRules.Position(mm, travelMm) is { } rule)
        {
            throw new UsageException(string.Create(CultureInfo.InvariantCulture, $"{name} {mm}: {rule}"));
        }
    }

    private static Option<string?> ProfileOption() => new("--profile") { Description = "Machine profile (JSON); default: two Zaber T-LA60A" };

    private static MachineProfile LoadProfile(ParseResult result, Option<string?> profile) =>
        result.GetValue(profile) is { } path ? MachineProfile.Load(path) : MachineProfile.Default;

    private static async Task<int> WithMovesAsync(ParseResult result, MachineOptions machine, MachineProfile profile, Core.Planning.ProcessSettings? process, Func<StageTestMoves, Task<string>> move)
    {
        var session = machine.Open(result, profile).Session;
        await using (session)
        {
            var moves = new StageTestMoves(session.Stage, session.Gate, profile, process, session.TimeProvider);
            result.InvocationConfiguration.Output.WriteLine(await session.RunAsync(() => move(moves)));
        }

        return CliRunner.Ok;
    }

    private static string Describe(StagePosition position, MachineProfile profile) => string.Create(
        CultureInfo.InvariantCulture,
        $"at {position.XMicrosteps}, {position.YMicrosteps} microsteps = {StageUnits.MicrostepsToMm(position.XMicrosteps, profile.X.MicrostepUm):0.####}, {StageUnits.MicrostepsToMm(position.YMicrosteps, profile.Y.MicrostepUm):0.####} mm; {LaserOffWords(profile)}");

    // Never "off" for a gate that cannot say so.
    private static string LaserOffWords(MachineProfile profile) =>
        profile.Gate.NeverReplies ? "laser sent off (this gate never replies, so nothing confirms it)" : "laser off";
}
