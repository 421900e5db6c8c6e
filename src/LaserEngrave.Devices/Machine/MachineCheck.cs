using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Motion;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.LaserGate;
using LaserEngrave.Devices.Zaber;

namespace LaserEngrave.Devices.Machine;

/// <summary>
/// The first day on a machine (`laserengrave machine check`, docs/commissioning.md): identifies both axes and the gate,
/// homes, moves each axis a known distance and reads it back, measures the latencies, and trips the gate's watchdog once
/// when the person at the machine has confirmed the beam is blocked.
/// </summary>
/// <remarks>Each step is checked against the machine profile; a step that fails is reported as failed and the rest still runs where it safely can.</remarks>
public sealed class MachineCheck
{
    private readonly IStage _stage;
    private readonly ILaserGate _gate;
    private readonly ILatencyProbe _latency;
    private readonly MachineProfile _profile;
    private readonly TimeProvider _time;
    private readonly string _laserPort;

    /// <summary>The check of the machine on a Zaber chain and a PIC gate, its latencies by <see cref="LatencyProbe"/>.</summary>
    public MachineCheck(ZaberChain stage, PicLaserGate gate, MachineProfile profile, TimeProvider timeProvider)
        : this(stage, gate, new LatencyProbe(stage, gate, timeProvider), profile, timeProvider, gate?.PortName ?? string.Empty)
    {
    }

    /// <summary>The check of any stage and gate (the app's connection, a test's fakes).</summary>
    /// <param name="laserPort">The gate's port, as the gate's step names it.</param>
    public MachineCheck(IStage stage, ILaserGate gate, ILatencyProbe latency, MachineProfile profile, TimeProvider timeProvider, string laserPort)
    {
        ArgumentNullException.ThrowIfNull(stage);
        ArgumentNullException.ThrowIfNull(gate);
        ArgumentNullException.ThrowIfNull(latency);
        ArgumentNullException.ThrowIfNull(profile);
        ArgumentNullException.ThrowIfNull(timeProvider);
        ArgumentNullException.ThrowIfNull(laserPort);
        _stage = stage;
        _gate = gate;
        _latency = latency;
        _profile = profile;
        _time = timeProvider;
        _laserPort = laserPort;
    }

    /// <summary>The steps in the order they run, as the report names them.</summary>
    public static IReadOnlyList<string> StepNames { get; } = ["laser gate", "X axis", "Y axis", "homing", "X move", "Y move", "latencies", "gate watchdog"];

    /// <summary>Runs every step; the laser is switched off at the end whatever happened.</summary>
    /// <param name="distanceMm">How far each axis is moved from home and read back.</param>
    /// <param name="exchanges">Round trips per device for the latencies.</param>
    /// <param name="tripWatchdog">The person confirmed the beam is blocked: the gate fires at a low frequency until its watchdog switches it off.</param>
    /// <param name="cancellationToken">Stops the check (the laser is still switched off).</param>
    /// <param name="progress">Told each step as it ends, in order.</param>
    public async Task<MachineCheckReport> RunAsync(double distanceMm, int exchanges, bool tripWatchdog, CancellationToken cancellationToken, IProgress<MachineCheckStep>? progress = null)
    {
        var steps = new StepList(progress);
        var c = CultureInfo.InvariantCulture;
        try
        {
            LaserGateKind? kindFound = null;
            var gateId = await Step(steps, "laser gate", async () =>
            {
                var id = await _gate.IdentifyAsync(cancellationToken);
                await _gate.OffAsync(cancellationToken);
                var (kind, found) = await GateKindAsync(cancellationToken);
                kindFound = kind;
                var text = $"{id} on {_laserPort}, switched off; {found}";
                if (kind == LaserGateKind.FrequencyOnly && _profile.Gate.CountsBursts)
                {
                    // The profile promises a burst and a watchdog this gate does not have: no run may count on them.
                    throw new DeviceException($"{text}, but the profile says countedBurst: set gate.kind to frequencyOnly and gate.watchdogMs to 0 (docs/machine-profile.md), or flash the gate's firmware");
                }

                return text;
            });
            AxisIdentity? x = null;
            AxisIdentity? y = null;
            foreach (var (axis, profile, name) in new[] { (_stage.X, _profile.X, "X"), (_stage.Y, _profile.Y, "Y") })
            {
                await Step(steps, $"{name} axis", async () =>
                {
                    var identity = await axis.IdentifyAsync(cancellationToken);
                    if (name == "X")
                    {
                        x = identity;
                    }
                    else
                    {
                        y = identity;
                    }

                    var travelMm = Units.StepsToMm(identity.MaximumPosition, profile.MicrostepUm);
                    var firmware = identity.FirmwareVersion;
                    var homing = ZaberFirmware.HasHomeSpeed(firmware) ? "homes at Set Home Speed" : "homes at the Target Speed (no Set Home Speed before 5.20)";
                    var known = ZaberFirmware.IsKnown(firmware) ? string.Empty : "; a firmware the manual does not describe: engrave step by step (--strategy paper)";
                    var text = string.Create(c, $"{Describe(axis, name)}: device ID {identity.DeviceId}, firmware {identity.FirmwareText} ({homing}{known}), resolution {profile.MicrostepUm:0.########} µm a microstep (the profile's), travel limit {travelMm:0.###} mm (the device's Maximum Position setting, {identity.MaximumPosition} microsteps)");
                    if (identity.MaximumPosition < profile.TravelMicrosteps)
                    {
                        throw new DeviceException(string.Create(c, $"{text}, shorter than the profile's {profile.TravelMm:0.###} mm: correct the profile's travel or the device's Maximum Position"));
                    }

                    return text;
                });
            }

            var speed = StageUnits.SpeedData(ProcessSettings.Default.TravelSpeedMmPerS, _profile.X.MicrostepUm);
            var acceleration = StageUnits.AccelerationData(ProcessSettings.Default.AccelerationMmPerS2, _profile.X.MicrostepUm);
            var homed = await Step(steps, "homing", async () =>
            {
                foreach (var axis in new[] { _stage.X, _stage.Y })
                {
                    await axis.SetAccelerationAsync(acceleration, cancellationToken);
                    await axis.SetHomeSpeedAsync(speed, cancellationToken);
                }

                var start = _time.GetTimestamp();
                var positions = await Task.WhenAll(_stage.X.HomeAsync(cancellationToken), _stage.Y.HomeAsync(cancellationToken));
                return string.Create(c, $"both axes homed in {_time.GetElapsedTime(start).TotalSeconds:0.0} s, at {positions[0]} and {positions[1]} microsteps");
            });

            if (homed is not null)
            {
                foreach (var (axis, profile, name) in new[] { (_stage.X, _profile.X, "X"), (_stage.Y, _profile.Y, "Y") })
                {
                    await Step(steps, $"{name} move", async () =>
                    {
                        var target = (long)Math.Round(Units.MmToSteps(Math.Min(distanceMm, profile.TravelMm), profile.MicrostepUm), MidpointRounding.AwayFromZero);
                        var moveSpeed = StageUnits.SpeedData(ProcessSettings.Default.TravelSpeedMmPerS, profile.MicrostepUm);
                        await axis.SetTargetSpeedAsync(moveSpeed, cancellationToken);
                        var start = _time.GetTimestamp();
                        var reached = await axis.MoveAbsoluteAsync(target, cancellationToken);
                        var seconds = _time.GetElapsedTime(start).TotalSeconds;
                        var read = await axis.GetPositionAsync(cancellationToken);
                        var expected = new TrapezoidProfile(target, StageUnits.SpeedMicrostepsPerS(moveSpeed), StageUnits.AccelerationMicrostepsPerS2(acceleration)).Duration;
                        var text = string.Create(c, $"{Describe(axis, name)} sent to {target} microsteps ({Units.StepsToMm(target, profile.MicrostepUm):0.###} mm): replied {reached}, reads {read}, in {Units.SecondsToMs(seconds):0} ms (the motion alone {Units.SecondsToMs(expected):0} ms)");
                        if (reached != target || read != target)
                        {
                            throw new DeviceException($"{text}: not where it was sent");
                        }

                        await axis.MoveAbsoluteAsync(0, cancellationToken);
                        return text;
                    });
                }
            }

            LatencyMeasurement? latency = null;
            await Step(steps, "latencies", async () =>
            {
                var measured = await _latency.MeasureAsync(exchanges, cancellationToken);
                var found = measured.ToProfile(_profile.Latency);
                try
                {
                    // What the profile cannot hold is not written: a computer this slow cannot time the laser's switching.
                    (_profile with { Latency = found }).Validate("the measured latencies");
                }
                catch (ProfileException ex)
                {
                    throw new DeviceException(string.Create(c, $"round trips up to {Math.Max(measured.X.MaxMs, measured.Gate.MaxMs):0.#} ms: {ex.Message}; free this computer of other work and check again"));
                }

                latency = measured;
                return string.Create(c, $"stage {found.StageMs:0.###} ± {found.StageJitterMs:0.###} ms, gate {found.GateMs:0.###} ± {found.GateJitterMs:0.###} ms one way ({exchanges} round trips each; X max {latency.X.MaxMs:0.##} ms, Y max {latency.Y.MaxMs:0.##} ms, gate max {latency.Gate.MaxMs:0.##} ms)");
            });

            if (!_profile.Gate.HasWatchdog)
            {
                // Nothing to trip: the profile says so, and every run asks the person to accept it.
                steps.Add(new MachineCheckStep("gate watchdog", MachineCheckResult.Skipped, $"none to trip (gate.kind frequencyOnly): {LaserGateProfile.NoWatchdogSentence}"));
            }
            else if (tripWatchdog)
            {
                await Step(steps, "gate watchdog", () => TripWatchdogAsync(cancellationToken));
            }
            else
            {
                steps.Add(new MachineCheckStep("gate watchdog", MachineCheckResult.Skipped, "not tripped: nobody confirmed the beam was blocked"));
            }

            return new MachineCheckReport(steps.Steps, x, y, gateId, latency?.ToProfile(_profile.Latency))
            {
                GateKindFound = kindFound,
                NoWatchdog = !_profile.Gate.HasWatchdog,
            };
        }
        finally
        {
            try
            {
                await _gate.OffAsync(CancellationToken.None);
            }
            catch (DeviceException)
            {
                // Reported by its step; the watchdog switches it off anyway.
            }

            if (cancellationToken.IsCancellationRequested)
            {
                // Stopped by the person: an axis homing or moving for the check stops where it is, not at its target.
                try
                {
                    await Task.WhenAll(_stage.X.StopAsync(CancellationToken.None), _stage.Y.StopAsync(CancellationToken.None));
                }
                catch (DeviceException)
                {
                    // Nothing more to do from here: the axis is reported by the panel's next reading.
                }
            }
        }
    }

    /// <summary>
    /// Which kind of gate answers: the counted-burst gate reports its state (STATE?), a frequency-only one does not know
    /// the command. Asked whatever the profile says, so a profile that describes the wrong gate is caught.
    /// </summary>
    private async Task<(LaserGateKind? Kind, string Found)> GateKindAsync(CancellationToken cancellationToken)
    {
        var gate = _profile.Gate;
        if (gate.NeverReplies)
        {
            return (null, "a gate that never replies (the profile's gate.neverReplies): its kind cannot be asked; the profile says frequencyOnly, and nothing confirms a command it is sent");
        }

        try
        {
            if (gate.CountsBursts)
            {
                var state = await _gate.GetStateAsync(cancellationToken);
                return (LaserGateKind.CountedBurst, string.Create(CultureInfo.InvariantCulture, $"found a counted-burst gate with a watchdog (it reports its state: watchdog {state.WatchdogMs} ms)"));
            }

            if (_gate is PicLaserGate pic)
            {
                // The default protocol's state command, which the profile of a frequency-only gate need not spell.
                var status = string.IsNullOrWhiteSpace(gate.StatusCommand) ? new LaserGateProfile().StatusCommand : gate.StatusCommand;
                var reply = await pic.SendAsync(status, "STATE", cancellationToken);
                if (PicLaserGate.ParseState(reply) is not null)
                {
                    return (LaserGateKind.CountedBurst, $"found a counted-burst gate with a watchdog (it reports its state), though the profile says frequencyOnly: set gate.kind to countedBurst to use its burst and watchdog");
                }
            }
            else
            {
                return (null, "the profile says frequencyOnly (its kind not asked on this connection)");
            }
        }
        catch (DeviceException ex) when (ex is LaserGateException or DeviceTimeoutException)
        {
            return (LaserGateKind.FrequencyOnly, $"found a frequency-only gate: it does not report its state ({ex.Message}), so it has no counted burst and no watchdog");
        }

        return (LaserGateKind.FrequencyOnly, "found a frequency-only gate: its answer to the state command is not a state");
    }

    // Fires at the profile's frame frequency and stays silent past the watchdog time: the gate must switch itself off and say so.
    private async Task<string> TripWatchdogAsync(CancellationToken cancellationToken)
    {
        var watchdog = _profile.Gate.WatchdogMs;
        await _gate.SetWatchdogAsync(watchdog, cancellationToken);
        await _gate.GetStateAsync(cancellationToken);
        var hz = Math.Min(_profile.MaxFrameFrequencyHz, _profile.Gate.MaxFrequencyHz);
        await _gate.SetFrequencyAsync(hz, cancellationToken);
        var start = _time.GetTimestamp();
        await Task.Delay(TimeSpan.FromMilliseconds(watchdog * 1.5), _time, cancellationToken);
        var state = await _gate.GetStateAsync(cancellationToken);
        var text = string.Create(CultureInfo.InvariantCulture, $"fired at {hz} Hz and fell silent: after {_time.GetElapsedTime(start).TotalMilliseconds:0} ms the gate reports {(state.Firing ? "still firing" : "off")}, watchdog {(state.WatchdogTripped ? "tripped" : "not tripped")} ({watchdog} ms)");
        if (state.Firing || !state.WatchdogTripped)
        {
            await _gate.OffAsync(cancellationToken);
            throw new DeviceException($"{text}: the watchdog does not switch the laser off; do not engrave until it does");
        }

        return text;
    }

    // As the Zaber chain names its devices ("device 1 (X)").
    private static string Describe(IStageAxis axis, string name) => $"device {axis.DeviceNumber} ({name})";

    private static async Task<string?> Step(StepList steps, string name, Func<Task<string>> step)
    {
        try
        {
            var text = await step();
            steps.Add(new MachineCheckStep(name, MachineCheckResult.Passed, text));
            return text;
        }
        catch (DeviceException ex)
        {
            steps.Add(new MachineCheckStep(name, MachineCheckResult.Failed, ex.Message));
            return null;
        }
    }

    // The steps so far, each told to the progress as it is added.
    private sealed class StepList(IProgress<MachineCheckStep>? progress)
    {
        public List<MachineCheckStep> Steps { get; } = [];

        public void Add(MachineCheckStep step)
        {
            Steps.Add(step);
            progress?.Report(step);
        }
    }
}

/// <summary>How a step of <see cref="MachineCheck"/> went.</summary>
public enum MachineCheckResult
{
    Passed,
    Failed,
    Skipped,
}

/// <summary>One step of a machine check and what it found, in one line.</summary>
public sealed record MachineCheckStep(string Name, MachineCheckResult Result, string Finding);

/// <summary>What a machine check found: its steps, both axes, the gate and the measured latencies (null where a step failed).</summary>
public sealed record MachineCheckReport(IReadOnlyList<MachineCheckStep> Steps, AxisIdentity? X, AxisIdentity? Y, string? Gate, LatencyProfile? Latency)
{
    /// <summary>Which kind of gate the check found answering (null when it could not ask).</summary>
    public LaserGateKind? GateKindFound { get; init; }

    /// <summary>The profile's gate has no watchdog (frequency-only): its watchdog step has nothing to trip.</summary>
    public bool NoWatchdog { get; init; }

    /// <summary>Every step passed (a skipped watchdog trip is not a pass, unless the gate has no watchdog to trip).</summary>
    public bool Passed => Steps.All(s => s.Result == MachineCheckResult.Passed || (NoWatchdog && s.Name == "gate watchdog" && s.Result == MachineCheckResult.Skipped));

    /// <summary>The printable report: a heading, the date, one line per step.</summary>
    public IEnumerable<string> Lines(string machine, DateTimeOffset at)
    {
        yield return $"LaserEngrave machine check: {machine}";
        yield return $"Date: {at.ToString("yyyy-MM-dd HH:mm", CultureInfo.InvariantCulture)}";
        foreach (var step in Steps)
        {
            var mark = step.Result switch { MachineCheckResult.Passed => "ok    ", MachineCheckResult.Failed => "FAILED", _ => "skip  " };
            yield return $"{mark} {step.Name}: {step.Finding}";
        }

        yield return Passed
            ? NoWatchdog ? "Result: every step passed; this gate has no watchdog, which each run asks you to accept" : "Result: every step passed"
            : "Result: NOT every step passed; fix what failed (docs/commissioning.md) before engraving";
    }
}
