using System.CommandLine;
using System.Globalization;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.LaserGate;

namespace LaserEngrave.Cli.Commands;

/// <summary>`laserengrave laser --port P (identify | on HZ | off | status)`: check the laser gate's wiring.</summary>
internal static class LaserCommand
{
    /// <summary>Longest timed `laser on`, s (a day); longer is a typo, and Ctrl+C ends an untimed one.</summary>
    private const int MaxOnSeconds = 86_400;

    public static Command Create()
    {
        var options = new DeviceOptions();
        var command = new Command("laser", "Check the laser gate: identify it, fire it, switch it off, read its state");
        options.AddTo(command);

        var identify = new Command("identify", "Ask the gate who it is");
        identify.SetAction((result, ct) => RunAsync(options, result, async (gate, output, token) =>
            output.WriteLine($"{gate.PortName}: {await gate.IdentifyAsync(token).ConfigureAwait(false)}"), ct));

        var hz = new Argument<int>("HZ") { Description = "Q-switch frequency in Hz (pulses per second)" };
        var seconds = new Option<double?>("--seconds") { Description = "Switch off after this many seconds (default: at Ctrl+C)" };
        var accept = new Option<bool>("--accept-no-watchdog") { Description = "Fire a laser gate that has no watchdog (a frequencyOnly profile): if this computer hangs while the laser fires, only the interlock or the key switch stops it" };
        var on = new Command("on", "Fire at HZ while this command runs (watchdog fed), and switch off at Ctrl+C, after --seconds, or on any fault") { hz, seconds, accept };
        on.SetAction((result, ct) =>
        {
            // Checked before the port opens: a bad number must never reach the gate.
            var profile = options.LoadProfile(result);
            CheckFire(profile, result.GetValue(hz), result.GetValue(seconds));
            if (!profile.Gate.HasWatchdog && !result.GetValue(accept))
            {
                throw new UsageException($"{Core.Geometry.LaserGateProfile.NoWatchdogSentence}; give --accept-no-watchdog to accept it");
            }

            return RunAsync(options, result, (gate, output, token) => FireAsync(gate, output, result.GetValue(hz), result.GetValue(seconds), token), ct);
        });

        var off = new Command("off", "Stop firing");
        off.SetAction((result, ct) => RunAsync(options, result, async (gate, output, token) =>
        {
            await gate.OffAsync(token).ConfigureAwait(false);
            output.WriteLine($"{gate.PortName}: laser off");
        }, ct));

        var status = new Command("status", "Show the frequency, whether it fires, and the watchdog");
        status.SetAction((result, ct) => RunAsync(options, result, async (gate, output, token) =>
        {
            var state = await gate.GetStateAsync(token).ConfigureAwait(false);
            output.WriteLine(string.Create(
                CultureInfo.InvariantCulture,
                $"{gate.PortName}: {state.FrequencyHz} Hz, {(state.Firing ? "firing" : "not firing")}, watchdog {(state.WatchdogMs > 0 ? $"{state.WatchdogMs} ms" : "off")}{(state.WatchdogTripped ? ", watchdog tripped since the last status" : string.Empty)}"));
        }, ct));

        command.Subcommands.Add(identify);
        command.Subcommands.Add(on);
        command.Subcommands.Add(off);
        command.Subcommands.Add(status);
        return command;
    }

    private static async Task<int> RunAsync(
        DeviceOptions options, ParseResult result, Func<PicLaserGate, TextWriter, CancellationToken, Task> action, CancellationToken cancellationToken)
    {
        var profile = options.LoadProfile(result);
        await using var gate = PicLaserGate.Open(options.PortName(result), profile.Gate);
        await action(gate, result.InvocationConfiguration.Output, cancellationToken).ConfigureAwait(false);
        return 0;
    }

    private static void CheckFire(Core.Geometry.MachineProfile profile, int frequencyHz, double? seconds)
    {
        if (frequencyHz <= 0)
        {
            throw new UsageException($"HZ must be above 0 (got {frequencyHz}); use `laser off` to stop");
        }

        OptionChecks.InRange(frequencyHz, 1, profile.Gate.MaxFrequencyHz, "HZ", " Hz", "the profile's gate.maxFrequencyHz");
        if (seconds is { } s && !(s > 0 && s <= MaxOnSeconds))
        {
            throw new UsageException($"--seconds {OptionChecks.N(s)}: must be above 0 and at most {MaxOnSeconds} (leave it out to fire until Ctrl+C)");
        }
    }

    private static async Task FireAsync(PicLaserGate gate, TextWriter output, int frequencyHz, double? seconds, CancellationToken cancellationToken)
    {

        var watchdogMs = gate.Profile.WatchdogMs;
        if (watchdogMs > 0)
        {
            await gate.SetWatchdogAsync(watchdogMs, cancellationToken).ConfigureAwait(false);
        }

        try
        {
            await gate.SetFrequencyAsync(frequencyHz, cancellationToken).ConfigureAwait(false);
            output.WriteLine(seconds is { } s
                ? string.Create(CultureInfo.InvariantCulture, $"{gate.PortName}: laser on at {frequencyHz} Hz for {s} s")
                : $"{gate.PortName}: laser on at {frequencyHz} Hz; press Ctrl+C to switch it off");
            await KeepFiringAsync(gate, watchdogMs, seconds, cancellationToken).ConfigureAwait(false);
        }
        catch
        {
            // Whatever went wrong (Ctrl+C while switching on included), the laser must not stay on.
            try
            {
                await gate.OffAsync(CancellationToken.None).ConfigureAwait(false);
            }
            catch (DeviceException)
            {
                // The first failure is the one worth reporting; this one usually has the same cause.
            }

            throw;
        }

        await gate.OffAsync(CancellationToken.None).ConfigureAwait(false);
        output.WriteLine($"{gate.PortName}: laser off");
    }

    /// <summary>Feeds the watchdog until the time is up or Ctrl+C.</summary>
    private static async Task KeepFiringAsync(PicLaserGate gate, int watchdogMs, double? seconds, CancellationToken cancellationToken)
    {
        // The gate switches itself off when it hears nothing for the watchdog time, so feed it well within that.
        var time = TimeProvider.System;
        var feed = TimeSpan.FromMilliseconds(watchdogMs > 0 ? Math.Clamp(watchdogMs / 3, 20, 1000) : 1000);
        var until = seconds is { } limit ? time.GetTimestamp() + (long)(limit * time.TimestampFrequency) : long.MaxValue;
        try
        {
            while (time.GetTimestamp() < until)
            {
                var left = time.GetElapsedTime(time.GetTimestamp(), until);
                await Task.Delay(left < feed ? left : feed, time, cancellationToken).ConfigureAwait(false);

                // A frequency-only gate has no watchdog to feed: only the time (or Ctrl+C) ends its firing.
                if (gate.Profile.CountsBursts)
                {
                    await gate.KeepAliveAsync(cancellationToken).ConfigureAwait(false);
                }
            }
        }
        catch (OperationCanceledException) when (cancellationToken.IsCancellationRequested)
        {
            // Ctrl+C: the caller switches the laser off and the command ends normally.
        }
    }
}
