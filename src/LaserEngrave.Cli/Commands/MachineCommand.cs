using System.CommandLine;
using System.Globalization;
using System.Text.Json;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Devices.Machine;
using LaserEngrave.Devices.Scheduling;

namespace LaserEngrave.Cli.Commands;

/// <summary>`laserengrave machine latency`: measures the machine's own serial latencies and keeps them in the profile's latency section.</summary>
internal static class MachineCommand
{
    /// <summary>Most round trips per device one measurement may ask for (about 25 minutes on the gate at 9600 baud).</summary>
    internal const int MaxExchanges = 100_000;

    public static Command Create()
    {
        var command = new Command("machine", "Measure the machine itself: its serial latencies (kept in the profile for timed laser switching)");
        command.Subcommands.Add(Latency());
        command.Subcommands.Add(Check());
        return command;
    }

    private static Command Latency()
    {
        var machine = new MachineOptions();
        var profile = new Option<string?>("--profile") { Description = "Machine profile (JSON) of the machine; with --write the measured latency section is stored in it (created from the default when missing)" };
        var count = new Option<int>("--count") { Description = "Round trips per device (each axis and the gate)", DefaultValueFactory = _ => 200 };
        var write = new Option<bool>("--write") { Description = "Store the measured latencies in --profile's latency section (gate processing kept)" };
        var json = new Option<bool>("--json") { Description = "Print one JSON object" };
        var command = new Command("latency", "Time hundreds of round trips to both axes (Zaber Echo Data) and the gate (its keepalive), report mean and jitter, and derive the one-way adapter latencies") { profile, count, write, json };
        machine.AddTo(command);
        command.SetAction(async (result, ct) =>
        {
            var exchanges = result.GetValue(count);
            OptionChecks.InRange(exchanges, 1, MaxExchanges, "--count", string.Empty, "round trips per device");
            var path = result.GetValue(profile);
            var store = result.GetValue(write);
            if (store && path is null)
            {
                throw new UsageException("--write needs --profile FILE: the profile to store the latency section in");
            }

            var existing = path is null ? MachineProfile.Default : File.Exists(path) || !store ? MachineProfile.Load(path) : MachineProfile.Default;
            LatencyMeasurement measured;

            // Measured at the priority a run gets, so that the profile describes what a run will see.
            using var priority = result.GetValue(machine.Simulate) ? null : RunPriority.Raise();
            var session = machine.Open(result, existing).Session;
            await using (session)
            {
                var probe = new LatencyProbe(session.Stage, session.Gate, session.TimeProvider);
                measured = await session.RunAsync(() => probe.MeasureAsync(exchanges, ct));
            }

            var latency = measured.ToProfile(existing.Latency);
            if (store)
            {
                // A profile that would not load again is not written (round trips beyond what timed switching can use).
                (existing with { Latency = latency }).Validate(path!);
                (existing with { Latency = latency }).Save(path!);
            }

            var stdout = result.InvocationConfiguration.Output;
            if (result.GetValue(json))
            {
                CliJson.Write(stdout, new LatencySummary(path, store, measured.X, measured.Y, measured.Stage, measured.Gate, measured.Host, latency));
                return CliRunner.Ok;
            }

            foreach (var trips in new[] { measured.X, measured.Y, measured.Gate })
            {
                stdout.WriteLine(Describe(trips));
            }

            var c = CultureInfo.InvariantCulture;
            stdout.WriteLine(string.Create(c, $"Stage adapter:    {latency.StageMs:0.###} ± {latency.StageJitterMs:0.###} ms one way (round trip - wire, halved; spread from the standard deviation or the furthest round trip, the larger)"));
            stdout.WriteLine(string.Create(c, $"Gate adapter:     {latency.GateMs:0.###} ± {latency.GateJitterMs:0.###} ms one way (round trip - wire - processing, halved)"));
            stdout.WriteLine(string.Create(c, $"Gate processing:  {latency.GateProcessingMs:0.###} ± {latency.GateProcessingJitterMs:0.###} ms, kept from the profile: a round trip cannot tell it from the adapter's"));
            var fastest = SpeedHold.FastestMmPerS(existing with { Latency = latency }, scheduled: false);
            stdout.WriteLine(string.Create(c, $"Host lateness:    {latency.HostLatenessMs:0.###} ms (98 % of {measured.Host?.Count ?? 0} timed waits within it), {latency.HostLatenessTailMs:0.###} ms at most: the fastest host-timed burn speed is the edge tolerance over the first ({fastest:0.##} mm/s on a gate without AFTER)"));
            stdout.WriteLine(store ? $"Written:          the latency section of {path}" : "Not written:      give --profile FILE --write to store it");
            return CliRunner.Ok;
        });
        return command;
    }

    private static Command Check()
    {
        var machine = new MachineOptions();
        var profile = new Option<string?>("--profile") { Description = "Machine profile (JSON) of the machine; with --write the measured latency section is stored in it (created from the default when missing)" };
        var distance = new Option<double>("--distance-mm") { Description = "How far each axis is moved from home and read back, mm", DefaultValueFactory = _ => 10 };
        var count = new Option<int>("--count") { Description = "Round trips per device for the latencies", DefaultValueFactory = _ => 100 };
        var write = new Option<bool>("--write") { Description = "Store the measured latencies in --profile's latency section" };
        var report = new Option<string?>("--report") { Description = "Also write the printable report to this text file" };
        var yes = new Option<bool>("--yes") { Description = "The beam is blocked: trip the gate's watchdog without asking" };
        var json = new Option<bool>("--json") { Description = "Print one JSON object" };
        var command = new Command("check", "The first day on a machine: identify both axes and the gate, home, move each axis a known distance and read it back, measure the latencies, trip the gate's watchdog once (beam blocked), and report (docs/commissioning.md)") { profile, distance, count, write, report, yes, json };
        machine.AddTo(command);
        command.SetAction(async (result, ct) =>
        {
            var exchanges = result.GetValue(count);
            OptionChecks.InRange(exchanges, 1, MaxExchanges, "--count", string.Empty, "round trips per device");
            var mm = result.GetValue(distance);
            if (!double.IsFinite(mm) || mm <= 0 || mm > 1000)
            {
                throw new UsageException($"--distance-mm {mm.ToString(CultureInfo.InvariantCulture)} must be above 0 and at most the travel");
            }

            var path = result.GetValue(profile);
            var store = result.GetValue(write);
            if (store && path is null)
            {
                throw new UsageException("--write needs --profile FILE: the profile to store the latency section in");
            }

            var existing = path is null ? MachineProfile.Default : File.Exists(path) || !store ? MachineProfile.Load(path) : MachineProfile.Default;
            if (mm > Math.Min(existing.X.TravelMm, existing.Y.TravelMm))
            {
                throw new UsageException(string.Create(CultureInfo.InvariantCulture, $"--distance-mm {mm} is beyond the travel ({Math.Min(existing.X.TravelMm, existing.Y.TravelMm)} mm)"));
            }

            var reportPath = result.GetValue(report);
            var stdout = result.InvocationConfiguration.Output;
            var trip = result.GetValue(yes) || Confirm(stdout);
            using var priority = result.GetValue(machine.Simulate) ? null : RunPriority.Raise();
            var session = machine.Open(result, existing).Session;
            MachineCheckReport found;
            string where;
            DateTimeOffset at;
            await using (session)
            {
                where = $"stage on {session.StagePort}, laser gate on {session.LaserPort}";
                at = session.TimeProvider.GetUtcNow();
                var check = new MachineCheck(session.Stage, session.Gate, existing, session.TimeProvider);
                found = await session.RunAsync(() => check.RunAsync(mm, exchanges, trip, ct));
            }

            var written = store && found.Latency is not null;
            if (written)
            {
                (existing with { Latency = found.Latency! }).Save(path!);
            }

            var lines = found.Lines(where, at).ToList();
            lines.Add(written ? $"Written: the latency section of {path}" : "Not written: give --profile FILE --write to store the latencies");
            if (reportPath is not null)
            {
                File.WriteAllLines(reportPath, lines);
            }

            if (result.GetValue(json))
            {
                CliJson.Write(stdout, new MachineCheckSummary(found.Passed, found.GateKindFound is { } kind ? JsonNamingPolicy.CamelCase.ConvertName(kind.ToString()) : null, [.. found.Steps.Select(s => new MachineCheckStepSummary(s.Name, s.Result.ToString().ToLowerInvariant(), s.Finding))], found.Latency, path, written, reportPath));
            }
            else
            {
                foreach (var line in lines)
                {
                    stdout.WriteLine(line);
                }
            }

            return found.Passed ? CliRunner.Ok : 1;
        });
        return command;
    }

    // The watchdog step fires the laser: only after the person at the machine says the beam is blocked.
    private static bool Confirm(TextWriter stdout)
    {
        if (Console.IsInputRedirected)
        {
            return false;
        }

        stdout.Write("Trip the laser gate's watchdog once? The laser fires at a low frequency until the gate switches it off. Is the beam blocked? [y/N] ");
        var answer = Console.ReadLine();
        return answer is not null && answer.Trim().Equals("y", StringComparison.OrdinalIgnoreCase) || (answer?.Trim().Equals("yes", StringComparison.OrdinalIgnoreCase) ?? false);
    }

    private static string Describe(RoundTrips trips) => string.Create(
        CultureInfo.InvariantCulture,
        $"{trips.Device}: {trips.Count} round trips, min {trips.MinMs:0.###} / mean {trips.MeanMs:0.###} / max {trips.MaxMs:0.###} ms, spread ±{trips.SpreadMs:0.###} ms, standard deviation {trips.StdDevMs:0.###} ms (wire {trips.WireMs:0.###} ms)");
}

/// <summary>`machine latency --json`: the round trips measured and the latency section they give.</summary>
internal sealed record LatencySummary(string? Profile, bool Written, RoundTrips X, RoundTrips Y, RoundTrips Stage, RoundTrips Gate, HostWaits? Host, LatencyProfile Latency);

/// <summary>`machine check --json`: each step's result and what it found.</summary>
internal sealed record MachineCheckSummary(bool Passed, string? GateKind, IReadOnlyList<MachineCheckStepSummary> Steps, LatencyProfile? Latency, string? Profile, bool Written, string? Report);

/// <summary>One step of <see cref="MachineCheckSummary"/>; the result in lower case.</summary>
internal sealed record MachineCheckStepSummary(string Name, string Result, string Finding);
