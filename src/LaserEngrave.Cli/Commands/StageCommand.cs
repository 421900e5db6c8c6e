using System.CommandLine;
using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Zaber;

namespace LaserEngrave.Cli.Commands;

/// <summary>`laserengrave stage --port P (identify | home | position | move-abs X_UM Y_UM)`: check the Zaber wiring.</summary>
internal static class StageCommand
{
    private static readonly CultureInfo C = CultureInfo.InvariantCulture;

    public static Command Create()
    {
        var options = new DeviceOptions();
        var command = new Command("stage", "Check the Zaber stage: find the devices, home, read or move the position");
        options.AddTo(command);

        var identify = new Command("identify", "Find the devices on the port and show firmware, settings and position; re-enables auto-reply if it is off");
        identify.SetAction((result, ct) => RunAsync(options, result, IdentifyAsync, ct));

        var home = new Command("home", "Home both axes (they travel to the home sensor)");
        home.SetAction((result, ct) => RunAsync(options, result, HomeAsync, ct));

        var position = new Command("position", "Show where both axes are");
        position.SetAction((result, ct) => RunAsync(options, result, PositionAsync, ct));

        var xUm = new Argument<double>("X_UM") { Description = "X target in µm from home" };
        var yUm = new Argument<double>("Y_UM") { Description = "Y target in µm from home" };
        var moveAbs = new Command("move-abs", "Move both axes to an absolute position in µm (rounded once to whole microsteps)") { xUm, yUm };
        moveAbs.SetAction((result, ct) =>
        {
            // Checked before the port opens, so a target off the axis never reaches the stage.
            var profile = options.LoadProfile(result);
            ToMicrosteps("X", result.GetValue(xUm), profile.X);
            ToMicrosteps("Y", result.GetValue(yUm), profile.Y);
            return RunAsync(options, result, (chain, output, token) => MoveAbsoluteAsync(chain, output, result.GetValue(xUm), result.GetValue(yUm), token), ct);
        });

        command.Subcommands.Add(identify);
        command.Subcommands.Add(home);
        command.Subcommands.Add(position);
        command.Subcommands.Add(moveAbs);
        return command;
    }

    private static async Task<int> RunAsync(
        DeviceOptions options, ParseResult result, Func<ZaberChain, TextWriter, CancellationToken, Task> action, CancellationToken cancellationToken)
    {
        var profile = options.LoadProfile(result);
        await using var chain = ZaberChain.Open(options.PortName(result), profile);
        await action(chain, result.InvocationConfiguration.Output, cancellationToken).ConfigureAwait(false);
        return 0;
    }

    private static async Task IdentifyAsync(ZaberChain chain, TextWriter output, CancellationToken cancellationToken)
    {
        var discovery = await chain.DiscoverAsync(fixAutoReply: true, cancellationToken).ConfigureAwait(false);
        output.WriteLine($"{discovery.PortName}: {discovery.Devices.Count} Zaber device(s)");
        foreach (var device in discovery.Devices)
        {
            var axis = device.Role == "Y" ? chain.Profile.Y : chain.Profile.X;
            var role = device.Role is null ? string.Empty : $" ({device.Role})";
            output.WriteLine(string.Create(C, $"device {device.DeviceNumber}{role}: device ID {device.DeviceId}, firmware {device.FirmwareText}, {(device.IsHomed ? "homed" : "not homed")}, device mode 0x{device.DeviceMode:X}"));
            output.WriteLine(string.Create(C, $"  position {Describe(device.Position, axis)}, maximum {Describe(device.MaximumPosition, axis)}"));
            output.WriteLine(string.Create(C,
                $"  speed {device.SpeedData} ({StageUnits.MicrostepsToMm(StageUnits.SpeedMicrostepsPerS(device.SpeedData), axis.MicrostepUm):0.000} mm/s), acceleration {device.AccelerationData} ({StageUnits.MicrostepsToMm(StageUnits.AccelerationMicrostepsPerS2(device.AccelerationData), axis.MicrostepUm):0.0} mm/s²)"));
        }

        foreach (var note in discovery.Notes)
        {
            output.WriteLine($"note: {note}");
        }

        var missing = new[] { chain.X, chain.Y }.Where(a => discovery.Find(a.DeviceNumber) is null).ToList();
        if (missing.Count > 0)
        {
            throw new DeviceException($"{discovery.PortName}: {string.Join(" and ", missing.Select(a => a.Description))} did not answer");
        }
    }

    private static async Task HomeAsync(ZaberChain chain, TextWriter output, CancellationToken cancellationToken)
    {
        output.WriteLine($"{chain.Connection.PortName}: homing X and Y");
        await StopOnCancelAsync(chain, () => Task.WhenAll(chain.X.HomeAsync(cancellationToken), chain.Y.HomeAsync(cancellationToken)), cancellationToken).ConfigureAwait(false);
        await PositionAsync(chain, output, cancellationToken).ConfigureAwait(false);
    }

    private static async Task PositionAsync(ZaberChain chain, TextWriter output, CancellationToken cancellationToken)
    {
        var x = await chain.X.GetPositionAsync(cancellationToken).ConfigureAwait(false);
        var y = await chain.Y.GetPositionAsync(cancellationToken).ConfigureAwait(false);
        output.WriteLine($"X: {Describe(x, chain.Profile.X)}");
        output.WriteLine($"Y: {Describe(y, chain.Profile.Y)}");
    }

    private static async Task MoveAbsoluteAsync(ZaberChain chain, TextWriter output, double xUm, double yUm, CancellationToken cancellationToken)
    {
        var x = ToMicrosteps("X", xUm, chain.Profile.X);
        var y = ToMicrosteps("Y", yUm, chain.Profile.Y);
        output.WriteLine($"{chain.Connection.PortName}: moving to X {Describe(x, chain.Profile.X)}, Y {Describe(y, chain.Profile.Y)}");
        await StopOnCancelAsync(chain, () => Task.WhenAll(chain.X.MoveAbsoluteAsync(x, cancellationToken), chain.Y.MoveAbsoluteAsync(y, cancellationToken)), cancellationToken).ConfigureAwait(false);
        await PositionAsync(chain, output, cancellationToken).ConfigureAwait(false);
    }

    /// <summary>Runs a motion; on Ctrl+C the axes are told to stop before the command ends.</summary>
    private static async Task StopOnCancelAsync(ZaberChain chain, Func<Task> motion, CancellationToken cancellationToken)
    {
        try
        {
            await motion().ConfigureAwait(false);
        }
        catch (OperationCanceledException) when (cancellationToken.IsCancellationRequested)
        {
            await Task.WhenAll(chain.X.StopAsync(CancellationToken.None), chain.Y.StopAsync(CancellationToken.None)).ConfigureAwait(false);
            throw;
        }
    }

    /// <summary>Whole microsteps from an absolute position in µm, rounded once, inside the travel.</summary>
    private static long ToMicrosteps(string axisName, double um, AxisProfile axis)
    {
        if (!(um >= 0 && um <= Units.MmToUm(axis.TravelMm)))
        {
            throw new UsageException(string.Create(C, $"{axisName} {um} µm is outside the travel 0..{Units.MmToUm(axis.TravelMm):0} µm"));
        }

        var microsteps = (long)Math.Round(StageUnits.UmToMicrosteps(um, axis.MicrostepUm), MidpointRounding.AwayFromZero);
        if (microsteps < 0 || microsteps > axis.TravelMicrosteps)
        {
            throw new UsageException(string.Create(C, $"{axisName} {um} µm is outside the travel 0..{Units.MmToUm(axis.TravelMm):0} µm"));
        }

        return microsteps;
    }

    private static string Describe(long microsteps, AxisProfile axis) =>
        string.Create(C, $"{StageUnits.MicrostepsToUm(microsteps, axis.MicrostepUm):0.000} µm ({microsteps} microsteps)");
}
