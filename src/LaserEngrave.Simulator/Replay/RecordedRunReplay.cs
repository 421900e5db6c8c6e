using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Timing;

namespace LaserEngrave.Simulator.Replay;

/// <summary>
/// What a recorded run on real ports burned: its recording through a fresh twin (<see cref="WireReplay"/>), checked as
/// `engrave --simulate` checks a run, one image or drawing whole, a job of layers layer by layer.
/// </summary>
public static class RecordedRunReplay
{
    /// <summary>
    /// The twin the run spoke to: the stages' firmware as the log says they reported it (a 5.06 refuses what a 5.23 takes),
    /// standing where they reported they stood (so homing takes the time it took), on virtual time, with no injected
    /// faults and a host that is never late (its lateness is in the recorded times already).
    /// </summary>
    public static SimulatorOptions OptionsFor(RunRecord record, MachineProfile profile, IReadOnlyList<WireEvent> events, SimulatorOptions baseOptions)
    {
        ArgumentNullException.ThrowIfNull(record);
        ArgumentNullException.ThrowIfNull(baseOptions);
        var options = baseOptions with { HostLateness = HostLateness.None, RealTime = false, Paced = false, FaultSpec = null, StartMicrosteps = WireReplay.StartMicrosteps(profile, events) };
        if (record.Devices.FirstOrDefault(d => d.Role == "x axis") is { } x && decimal.TryParse(x.Firmware, NumberStyles.AllowDecimalPoint, CultureInfo.InvariantCulture, out var firmware))
        {
            options = options with { FirmwareVersion = (int)Math.Round(firmware * 100) };
        }

        return options;
    }

    /// <summary>Replays the run of one image (<paramref name="job"/>) or drawing; its figures and, for an image, the burn report (burned pixels, dose).</summary>
    public static async Task<(RunSimulation Simulation, BurnReport? Burn)> ReplayAsync(PreparedJob? job, PreparedDrawing? drawing, MachineProfile profile, IReadOnlyList<WireEvent> events, SimulatorOptions options, CancellationToken cancellationToken)
    {
        if ((job is null) == (drawing is null))
        {
            throw new ArgumentException("one image or one drawing");
        }

        var machine = SimulatedMachine.CreateInProcess(profile, options);
        await using (machine.ConfigureAwait(false))
        {
            var inspector = new BurnInspector(machine);
            inspector.Begin();
            await WireReplay.RunAsync(machine, events, cancellationToken).ConfigureAwait(false);
            return (Inspect(inspector, job, drawing), inspector.Report);
        }
    }

    /// <summary>
    /// Replays the run of a job of layers: each layer's burn checked alone, from its recorded start to the next's; null for
    /// a layer the recording does not start (it never ran, or an earlier run completed it).
    /// </summary>
    /// <exception cref="RunLogException">The recording notes no layer's start (made before layers were noted).</exception>
    public static async Task<IReadOnlyList<RunSimulation?>> ReplayLayersAsync(IReadOnlyList<PreparedLayer> parts, MachineProfile profile, IReadOnlyList<WireEvent> events, SimulatorOptions options, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(parts);
        ArgumentNullException.ThrowIfNull(events);
        if (events.All(e => e.Layer is null))
        {
            throw new RunLogException("the recording does not say where each layer began (it was made before replay of layers), so its layers' burns cannot be told apart");
        }

        if (events.FirstOrDefault(e => e.Layer >= parts.Count) is { } beyond)
        {
            throw new RunLogException(string.Create(CultureInfo.InvariantCulture, $"the recording starts layer {beyond.Layer + 1} but the job has {parts.Count}: it is not this run's recording"));
        }

        var results = new RunSimulation?[parts.Count];
        var machine = SimulatedMachine.CreateInProcess(profile, options);
        await using (machine.ConfigureAwait(false))
        {
            var inspector = new BurnInspector(machine);
            int? current = null;
            await WireReplay.RunAsync(machine, events, cancellationToken, layer =>
            {
                // As the run checks it: the layer before is over when the next begins.
                if (current is { } before)
                {
                    results[before] = Inspect(inspector, parts[before].Image, parts[before].Drawing);
                }

                inspector.Begin();
                current = layer;
            }).ConfigureAwait(false);
            if (current is { } last)
            {
                results[last] = Inspect(inspector, parts[last].Image, parts[last].Drawing);
            }
        }

        return results;
    }

    private static RunSimulation Inspect(BurnInspector inspector, PreparedJob? job, PreparedDrawing? drawing) =>
        job is not null ? inspector.Inspect(job) : inspector.InspectDrawing(drawing!);
}
