using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.LaserGate;
using LaserEngrave.Simulator.Motion;
using LaserEngrave.Simulator.Timing;

namespace LaserEngrave.Simulator.Replay;

/// <summary>
/// What a recorded run on real ports burned: its recording through a fresh twin (<see cref="WireReplay"/>), checked as
/// `engrave --simulate` checks a run, one image or drawing whole, a job of layers layer by layer.
/// </summary>
public static class RecordedRunReplay
{
    /// <summary>
    /// The twin the run spoke to (with <paramref name="recordedDelays"/>, adapters without latency of their own: each write
    /// goes in as late as its reply says it reached its device, <see cref="RecordedLatency"/>): the stages' firmware as the log says they reported it (a 5.06 refuses what a 5.23 takes),
    /// standing where they reported they stood (so homing takes the time it took), on virtual time, with no injected
    /// faults and a host that is never late (its lateness is in the recorded times already).
    /// </summary>
    /// <returns>The twin's options, and each event's delay (null: the twin's adapters draw theirs).</returns>
    public static ReplaySetup Setup(RunRecord record, MachineProfile profile, IReadOnlyList<WireEvent> events, SimulatorOptions baseOptions, bool recordedDelays = true)
    {
        ArgumentNullException.ThrowIfNull(record);
        ArgumentNullException.ThrowIfNull(baseOptions);
        var options = baseOptions with { HostLateness = HostLateness.None, RealTime = false, Paced = false, FaultSpec = null, StartMicrosteps = WireReplay.StartMicrosteps(profile, events) };
        RecordedDelays? delays = null;
        if (recordedDelays)
        {
            options = options with { AdapterLatency = Jitter.None };
            var commands = new GateCommandSet(profile.Gate);
            Func<byte[], double> processing = options.GateProcessing is { } drawn
                ? _ => Units.MsToSeconds(drawn.MeanMs)
                : command => GateFirmwareTiming.ProcessingSeconds(commands, command);
            delays = RecordedLatency.Estimate(profile, events, processing);
        }

        if (record.Devices.FirstOrDefault(d => d.Role == "x axis") is { } x && decimal.TryParse(x.Firmware, NumberStyles.AllowDecimalPoint, CultureInfo.InvariantCulture, out var firmware))
        {
            options = options with { FirmwareVersion = (int)Math.Round(firmware * 100) };
        }

        return new ReplaySetup(options, delays?.Seconds()) { Recorded = delays };
    }

    /// <summary>Replays the run of one image or drawing (<paramref name="job"/>); its figures and, for an image, the burn report (burned pixels, dose).</summary>
    public static async Task<(RunSimulation Simulation, BurnReport? Burn)> ReplayAsync(EngraveJob job, MachineProfile profile, IReadOnlyList<WireEvent> events, ReplaySetup setup, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(setup);
        var run = await RunOnceAsync(job, profile, events, setup.Options, setup.Delays, cancellationToken).ConfigureAwait(false);
        return (run.Simulation, run.Burn);
    }

    /// <summary>
    /// Replays the run of one image or drawing at the recorded delays' estimates, its stage's motion writes moved until
    /// the replay's stage reports the positions the run's stages reported (<see cref="ReportedPositionFit"/>), and, where
    /// the recording leaves a band open (<see cref="RecordedDelays"/>), at both ends of it as well: the stage's writes at
    /// their earliest and the gate's at their latest, then the other way round. What differs between the three is what
    /// the recording cannot tell: each switching's band in µm and the pixels burned in one and not in another.
    /// </summary>
    /// <returns>The estimate's figures and burn report, and the uncertainty (null when the setup has no recorded delays: the twin's adapters drew theirs).</returns>
    public static async Task<(RunSimulation Simulation, BurnReport? Burn, ReplayUncertainty? Uncertainty)> ReplayWithUncertaintyAsync(EngraveJob job, MachineProfile profile, IReadOnlyList<WireEvent> events, ReplaySetup setup, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(setup);
        if (setup.Recorded is not { } recorded)
        {
            var plain = await RunOnceAsync(job, profile, events, setup.Options, setup.Delays, cancellationToken).ConfigureAwait(false);
            return (plain.Simulation, plain.Burn, null);
        }

        Task<ReplayRun> Replay(IReadOnlyList<double> delays) => RunOnceAsync(job, profile, events, setup.Options, delays, cancellationToken);
        var (_, estimate, agreement) = await ReportedPositionFit.FitAsync(profile, events, recorded.Positions, recorded.Seconds(), Replay).ConfigureAwait(false);
        if (recorded.WidestSeconds < ReplayUncertainty.ResolutionSeconds)
        {
            // Every delay pinned: the ends of the bands are the estimate itself.
            return (estimate.Simulation, estimate.Burn, ReplayUncertainty.Compare(estimate, estimate, estimate, recorded, agreement));
        }

        // Each end of the bands with the stage's motion fitted again to its reports: a stage whose queries arrived earlier
        // stood where it said earlier, so its motion writes came earlier too.
        var (_, gateEarly, _) = await ReportedPositionFit.FitAsync(profile, events, recorded.Positions, recorded.Corner(events, gateLate: false), Replay, spill: false).ConfigureAwait(false);
        var (_, gateLate, _) = await ReportedPositionFit.FitAsync(profile, events, recorded.Positions, recorded.Corner(events, gateLate: true), Replay, spill: false).ConfigureAwait(false);
        return (estimate.Simulation, estimate.Burn, ReplayUncertainty.Compare(estimate, gateEarly, gateLate, recorded, agreement));
    }

    private static async Task<ReplayRun> RunOnceAsync(EngraveJob job, MachineProfile profile, IReadOnlyList<WireEvent> events, SimulatorOptions options, IReadOnlyList<double>? delays, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(job);
        if (job.Parts.Count != 1)
        {
            throw new ArgumentException("one image or one drawing (a job of layers replays by ReplayLayersAsync)", nameof(job));
        }

        var machine = SimulatedMachine.CreateInProcess(profile, options);
        await using (machine.ConfigureAwait(false))
        {
            var inspector = new BurnInspector(machine);
            inspector.Begin();
            var start = 0.0;
            await WireReplay.RunAsync(machine, events, cancellationToken, delays: delays, started: s => start = s).ConfigureAwait(false);
            var simulation = Inspect(inspector, job.Parts[0]);
            var recorder = machine.Recorder;
            var switches = recorder.LaserChanges
                .Select(c => new LaserSwitch(c.AtSeconds, c.FrequencyHz > 0, recorder.X.PositionAt(c.AtSeconds) * recorder.XMicrostepUm, recorder.Y.PositionAt(c.AtSeconds) * recorder.YMicrostepUm))
                .ToList();
            var axes = new Dictionary<byte, AxisTrajectory> { [profile.X.DeviceNumber] = recorder.X, [profile.Y.DeviceNumber] = recorder.Y };
            if (profile.Z is { } z && recorder.Z is { } zAxis)
            {
                axes[z.DeviceNumber] = zAxis;
            }

            return new ReplayRun(simulation, inspector.Report, switches, axes, start);
        }
    }

    /// <summary>
    /// Replays the run of a job of layers: each layer's burn checked alone, from its recorded start to the next's; null for
    /// a layer the recording does not start (it never ran, or an earlier run completed it).
    /// </summary>
    /// <exception cref="RunLogException">The recording notes no layer's start (made before layers were noted).</exception>
    public static async Task<IReadOnlyList<RunSimulation?>> ReplayLayersAsync(IReadOnlyList<JobPart> parts, MachineProfile profile, IReadOnlyList<WireEvent> events, ReplaySetup setup, CancellationToken cancellationToken)
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
        ArgumentNullException.ThrowIfNull(setup);
        var machine = SimulatedMachine.CreateInProcess(profile, setup.Options);
        await using (machine.ConfigureAwait(false))
        {
            var inspector = new BurnInspector(machine);
            int? current = null;
            await WireReplay.RunAsync(machine, events, cancellationToken, layer =>
            {
                // As the run checks it: the layer before is over when the next begins.
                if (current is { } before)
                {
                    results[before] = Inspect(inspector, parts[before]);
                }

                inspector.Begin();
                current = layer;
            }, setup.Delays).ConfigureAwait(false);
            if (current is { } last)
            {
                results[last] = Inspect(inspector, parts[last]);
            }
        }

        return results;
    }

    // The twin checks an image's burn pixel by pixel and a drawing's along its paths: the one place the kinds part here.
    private static RunSimulation Inspect(BurnInspector inspector, JobPart part) =>
        part switch
        {
            DrawingPart { Drawing: var drawing } => inspector.InspectDrawing(drawing),
            ImagePart { Image: var image } => inspector.Inspect(image),
            _ => throw new ArgumentException($"no inspection of a {part.GetType().Name}", nameof(part)),
        };
}

/// <summary>How a recording is replayed: the twin's options, and each event's delay from the recording (null: the twin's adapters draw their own).</summary>
public sealed record ReplaySetup(SimulatorOptions Options, IReadOnlyList<double>? Delays)
{
    /// <summary>The delays with the band each leaves open and what each link showed; null with the twin's own adapters.</summary>
    public RecordedDelays? Recorded { get; init; }
}
