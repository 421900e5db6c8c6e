using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Motion;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Programs;
using LaserEngrave.Core.Vectors;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Zaber;

namespace LaserEngrave.Devices.Execution;

/// <summary>
/// Preflight: the job against the machine, the gate and both axes identified and checked, homing, before anything moves
/// under the laser or fires (docs/execution.md, "How a run drives the machine"). The engine runs it once per run.
/// </summary>
/// <remarks>A refusal throws <see cref="PreflightException"/> with one line; nothing has moved under the laser.</remarks>
internal sealed class RunPreflight
{
    /// <summary>The widest spread a run assumes, in times the profile's (a profile this far off needs `machine latency`).</summary>
    public const double MaxLatencyScale = 8;

    private readonly IStage _stage;
    private readonly ILaserGate _gate;
    private readonly PartProgram _program;
    private readonly PreparedJob? _job;
    private readonly PreparedDrawing? _drawing;
    private readonly ProcessSettings _process;
    private readonly MachineProfile _profile;
    private readonly TimedSwitching? _timing;
    private readonly int _travelSpeedData;
    private readonly int _accelerationData;
    private readonly RunOptions _options;

    /// <param name="program">The part's program as planned: its kind decides what the firmware must vouch for.</param>
    /// <param name="job">The image job (raster or dots), or null for a drawing.</param>
    /// <param name="drawing">The drawing, or null for an image job.</param>
    /// <param name="timing">The plan's timing model (the drawing's schedule's for a drawing; null for a plan without one).</param>
    /// <param name="travelSpeedData">Set Target Speed data of the travel speed, the axes' Home Speed.</param>
    /// <param name="accelerationData">Set Acceleration data, for homing.</param>
    public RunPreflight(IStage stage, ILaserGate gate, PartProgram program, PreparedJob? job, PreparedDrawing? drawing, ProcessSettings process, MachineProfile profile,
        TimedSwitching? timing, int travelSpeedData, int accelerationData, RunOptions options)
    {
        if ((job is null) == (drawing is null))
        {
            throw new ArgumentException("preflight checks one image job or one drawing");
        }

        _stage = stage;
        _gate = gate;
        _program = program;
        _job = job;
        _drawing = drawing;
        _process = process;
        _profile = profile;
        _timing = timing;
        _travelSpeedData = travelSpeedData;
        _accelerationData = accelerationData;
        _options = options;
    }

    /// <summary>Checks the job, identifies and checks the gate and both axes, homes what is not homed; what the run starts from.</summary>
    /// <exception cref="PreflightException">Refused; nothing moved under the laser.</exception>
    public async Task<PreflightOutcome> RunAsync(CancellationToken token)
    {
        CheckGateKind();
        CheckJob();
        string gateIdentity;
        var gateVouchesForCut = true;
        var counted = _profile.Gate.CountsBursts;
        var scheduled = false;
        try
        {
            gateIdentity = await OnceMoreAfterTimeoutAsync(() => _gate.IdentifyAsync(token));
            if (_options.ResumeFrom is { OffByGateWatchdog: true } && (!counted || !(await _gate.GetStateAsync(token)).WatchdogTripped))
            {
                // The laser's switch-off time counted on the watchdog; a gate restarted since (or one without STATE?) cannot vouch for it.
                gateVouchesForCut = false;
            }

            await _gate.OffAsync(token);
            if (counted)
            {
                // A frequency-only gate has no watchdog to set: the person accepted that (CheckGateKind).
                await _gate.SetWatchdogAsync(_profile.Gate.WatchdogMs, token);

                // Only a timed raster sends scheduled switch-ons, and only to a gate that says it takes them (CAPS? lists AFTER).
                if (_program is RasterProgram { Timing: not null })
                {
                    scheduled = (await _gate.GetCapabilitiesAsync(token)).Contains(LaserGateCapabilities.After);
                }
            }
        }
        catch (DeviceException ex)
        {
            throw new PreflightException($"the laser gate does not answer as it should: {ex.Message}", ex);
        }

        // What this computer can hold with this gate, now that the gate said whether it times its switch-ons: refused
        // before anything moves rather than failing as timing doubts (SpeedHold, the one rule the front ends use too).
        if (_program is RasterProgram { Timing: not null } && SpeedHold.Problem(_process.BurnSpeedMmPerS, _profile, scheduled) is { } tooFast)
        {
            throw new PreflightException(tooFast);
        }

        var exchangesBefore = (_stage.X as IAxisFirmware)?.RoundTripsRecorded ?? 0;
        var x = await IdentifyAxisAsync(_stage.X, "X", token);
        var y = await IdentifyAxisAsync(_stage.Y, "Y", token);
        CheckFirmware(x, "X");
        CheckFirmware(y, "Y");
        CheckReach(x, y);
        // A gate whose watchdog did not trip heard a command that switched the laser off: the cut at the fault's first OFF.
        var resumeX = gateVouchesForCut ? _options.ResumeFrom?.ResumeXMicrosteps : _options.ResumeFrom?.OffResumeXMicrosteps;
        if (_options.ResumeFrom is { ResumeXMicrosteps: not null, ExpectedXMicrosteps: { } expected })
        {
            // The stage could not be asked when the run stopped: it must be found where its motion was taking it, or the
            // time the laser went off says nothing of where it burned, and the cut-off run is burned again from its start.
            try
            {
                if (!x.IsHomed || await _stage.X.GetPositionAsync(token) != expected)
                {
                    resumeX = null;
                }
            }
            catch (DeviceException ex)
            {
                throw new PreflightException($"the X axis does not answer: {ex.Message}", ex);
            }
        }

        var homing = new List<Task<long>>();
        long positionX, positionY;
        try
        {
            // Homing at the process' acceleration and travel speed, so it takes the time the estimate says, not the device's power-up settings'.
            foreach (var (axis, identity) in new[] { (_stage.X, x), (_stage.Y, y) })
            {
                if (_options.Home || !identity.IsHomed)
                {
                    await axis.SetAccelerationAsync(_accelerationData, token);
                    await axis.SetHomeSpeedAsync(_travelSpeedData, token);
                }
            }

            if (_options.Home || !x.IsHomed)
            {
                homing.Add(_stage.X.HomeAsync(token));
            }

            if (_options.Home || !y.IsHomed)
            {
                homing.Add(_stage.Y.HomeAsync(token));
            }

            await Task.WhenAll(homing);
            positionX = await _stage.X.GetPositionAsync(token);
            positionY = await _stage.Y.GetPositionAsync(token);
        }
        catch (DeviceException ex)
        {
            throw new PreflightException($"homing failed: {ex.Message}", ex);
        }

        // Raster timed switching only: a drawing's schedule and a step-by-step run keep the profile's latencies.
        var timing = _timing;
        var latencyScale = 1.0;
        var scale = Math.Max(double.IsFinite(_options.LatencyScale) ? Math.Max(1, _options.LatencyScale) : 1, SpreadSeenScale(exchangesBefore));
        if (scale > 1 && _program is RasterProgram { Timing: { } planned })
        {
            latencyScale = scale;

            // Guards, margins, run-ups and checks all follow from the latencies' spread: the run times itself with the wider one.
            var latency = _profile.Latency;
            var timedProfile = _profile with
            {
                Latency = latency with
                {
                    StageJitterMs = latency.StageJitterMs * latencyScale,
                    GateJitterMs = latency.GateJitterMs * latencyScale,
                    GateProcessingJitterMs = latency.GateProcessingJitterMs * latencyScale,
                },
            };
            timing = TimedSwitching.For(_process, timedProfile, planned.MicrostepUm);
        }

        return new PreflightOutcome(new MachineIdentity(x, y, gateIdentity), gateVouchesForCut, resumeX, homing.Count > 0, positionX, positionY, latencyScale, timing, scheduled);
    }

    private static string N(double value) => value.ToString("0.####", CultureInfo.InvariantCulture);

    /// <summary>Asks twice before giving up: the first line after a port opens can be lost (a device still waking, noise on the line).</summary>
    private static async Task<T> OnceMoreAfterTimeoutAsync<T>(Func<Task<T>> ask)
    {
        try
        {
            return await ask();
        }
        catch (DeviceTimeoutException)
        {
            return await ask();
        }
    }

    private async Task<AxisIdentity> IdentifyAxisAsync(IStageAxis axis, string name, CancellationToken token)
    {
        AxisIdentity identity;
        try
        {
            identity = await OnceMoreAfterTimeoutAsync(() => axis.IdentifyAsync(token));
            if (identity.AutoReplyDisabled)
            {
                if (!_options.FixAutoReply || axis is not IAxisFirmware firmware)
                {
                    throw new PreflightException(
                        $"the {name} axis (device {axis.DeviceNumber}) has auto-reply disabled (Device Mode bit 0), so it would never confirm a move; clear bit 0 first");
                }

                await firmware.ClearAutoReplyDisabledAsync(token);
                identity = await axis.IdentifyAsync(token);
            }
        }
        catch (DeviceException ex) when (ex is not PreflightException)
        {
            throw new PreflightException($"the {name} axis (device {axis.DeviceNumber}) does not answer as it should: {ex.Message}", ex);
        }

        return identity;
    }

    /// <summary>Refuses a run whose strategy needs what the axis' firmware does not vouch for (<see cref="ZaberFirmware"/>), naming the axis, the firmware and what is missing.</summary>
    private void CheckFirmware(AxisIdentity identity, string name)
    {
        var drawing = _program is DrawingProgram;
        var timedRaster = _program is RasterProgram { Timing: not null };
        var missing = ZaberFirmware.Missing(identity.FirmwareVersion, speedChangeMidMove: timedRaster, constantSpeed: drawing);
        if (missing.Count > 0)
        {
            var instead = timedRaster ? "; engrave it step by step (--strategy paper), which needs neither" : string.Empty;
            throw new PreflightException(
                $"the {name} axis (device {identity.DeviceNumber}) has firmware {identity.FirmwareText}, for which the Zaber manual does not vouch for {string.Join(" nor ", missing)}, which this job needs (T-series firmware 5.00-5.99 has it){instead}");
        }
    }

    /// <summary>
    /// A gate without a watchdog runs only once the person has accepted what then protects the laser (said in one
    /// sentence), and a frequency-only gate cannot count a dot's pulses: both refused before anything is sent.
    /// </summary>
    private void CheckGateKind()
    {
        var gate = _profile.Gate;
        if (!gate.HasWatchdog && !_options.AcceptNoWatchdog)
        {
            throw new PreflightException($"{LaserGateProfile.NoWatchdogSentence}; accept it to run (--accept-no-watchdog, or tick it in the Machine panel)");
        }

        if (!gate.CountsBursts && _program is DotProgram)
        {
            throw new PreflightException("dot mode fires an exact count of pulses at each dot, which only a gate that counts its bursts (BURST) can do; this profile's gate is frequencyOnly: engrave in raster mode");
        }
    }

    /// <summary>Refuses a job that leaves the travel or asks for speeds the stage cannot run.</summary>
    private void CheckJob()
    {
        if (_program is DrawingProgram program)
        {
            CheckDrawing(_drawing!, program);
        }
        else if (JobRules.Placement(_job!) is { } outside)
        {
            throw new PreflightException(outside);
        }

        var strategy = _program.Strategy;
        var microstepUm = _program.MicrostepUm;
        CheckSpeed("burn speed", _process.SpeedMmPerS(MoveKind.Burn, strategy));
        CheckSpeed("travel speed", _process.SpeedMmPerS(MoveKind.Travel, strategy));
        var accelerationUnits = Math.Round(StageUnits.MmToMicrosteps(_process.AccelerationMmPerS2, microstepUm) / StageUnits.AccelerationUnitMicrostepsPerS2);
        var maxAcceleration = Math.Min(_profile.X.MaxAccelerationMmPerS2, _profile.Y.MaxAccelerationMmPerS2);
        if (accelerationUnits < 1 || accelerationUnits > StageUnits.MaxSettingData || _process.AccelerationMmPerS2 > maxAcceleration)
        {
            throw new PreflightException(
                $"acceleration {N(_process.AccelerationMmPerS2)} mm/s² is outside what the stage takes ({N(Unit(StageUnits.AccelerationUnitMicrostepsPerS2))}..{N(maxAcceleration)} mm/s²)");
        }

        // After the speeds: a pixel too short for the gate names a burn speed that would work, which must be one the stage runs.
        if (_job?.EngraveProblem is { } tooShort)
        {
            throw new PreflightException(tooShort);
        }

        void CheckSpeed(string what, double mmPerS)
        {
            var units = Math.Round(StageUnits.MmToMicrosteps(mmPerS, microstepUm) / StageUnits.SpeedUnitMicrostepsPerS);
            var max = Math.Min(_profile.X.MaxSpeedMmPerS, _profile.Y.MaxSpeedMmPerS);
            if (units < 1 || units > StageUnits.MaxSettingData || mmPerS > max)
            {
                throw new PreflightException($"{what} {N(mmPerS)} mm/s is outside what the stage takes ({N(Unit(StageUnits.SpeedUnitMicrostepsPerS))}..{N(max)} mm/s)");
            }
        }

        double Unit(double microsteps) => StageUnits.MicrostepsToMm(microsteps, microstepUm);
    }

    /// <summary>Refuses a job that reaches past an axis' Maximum Position (the device's own limit may be below the profile's travel).</summary>
    private void CheckReach(AxisIdentity x, AxisIdentity y)
    {
        if (_program is DrawingProgram program)
        {
            CheckDrawingReach(program, x, y);
            return;
        }

        var plan = _job!.Plan;
        var geometry = plan.Geometry;
        var right = Math.Min(geometry.EdgeX(geometry.WidthPx) + plan.OverscanMicrosteps, geometry.TravelXMicrosteps);
        var bottom = geometry.EdgeY(geometry.HeightPx);
        foreach (var (name, reach, identity) in new[] { ("X", right, x), ("Y", bottom, y) })
        {
            if (identity.MaximumPosition > 0 && reach > identity.MaximumPosition)
            {
                throw new PreflightException(
                    $"the job reaches {name} = {N(StageUnits.MicrostepsToMm(reach, geometry.MicrostepUm))} mm but the {name} axis stops at {N(StageUnits.MicrostepsToMm(identity.MaximumPosition, geometry.MicrostepUm))} mm (its Maximum Position)");
            }
        }
    }

    /// <summary>Refuses a drawing that leaves the travel or has nothing to burn.</summary>
    private static void CheckDrawing(PreparedDrawing drawing, DrawingProgram program)
    {
        if (JobRules.Placement(drawing) is { } outside)
        {
            throw new PreflightException(outside);
        }

        if (program.StrokeCount == 0)
        {
            throw new PreflightException($"{drawing.Spec.ImagePath}: no path is long enough to burn");
        }
    }

    /// <summary>Refuses a drawing whose strokes (run-ups, paths and where the axes rest after them) reach past an axis' Maximum Position.</summary>
    private static void CheckDrawingReach(DrawingProgram program, AxisIdentity x, AxisIdentity y)
    {
        long right = long.MinValue, bottom = long.MinValue;
        foreach (var step in program.Steps())
        {
            var s = step.Stroke;
            right = Math.Max(right, Math.Max(Math.Max(s.RunUpStart.X, s.RestEnd.X), s.Path.Points.Max(p => p.X)));
            bottom = Math.Max(bottom, Math.Max(Math.Max(s.RunUpStart.Y, s.RestEnd.Y), s.Path.Points.Max(p => p.Y)));
        }

        foreach (var (name, reach, identity) in new[] { ("X", right, x), ("Y", bottom, y) })
        {
            if (identity.MaximumPosition > 0 && reach > identity.MaximumPosition)
            {
                throw new PreflightException(
                    $"the job reaches {name} = {N(StageUnits.MicrostepsToMm(reach, program.MicrostepUm))} mm but the {name} axis stops at {N(StageUnits.MicrostepsToMm(identity.MaximumPosition, program.MicrostepUm))} mm (its Maximum Position)");
            }
        }
    }

    /// <summary>
    /// The preflight's stage exchanges (identification, homing's settings and the positions after it: 14 to 22 commands
    /// that reply at once, one at a time) against the profile: their round trips may spread by the two adapter latencies'
    /// jitter, 4 J. Wider, the profile understates the latencies (or the computer's lateness) and the guards sized by it
    /// would let pulses past the edges; the run then assumes twice the ratio seen, since a dozen draws rarely show the
    /// largest. 1 when they fit, or for a plan without timing.
    /// </summary>
    private double SpreadSeenScale(long exchangesBefore)
    {
        if (_timing is null || _stage.X is not IAxisFirmware firmware)
        {
            return 1;
        }

        // Only the identification's, one at a time: during a run replies queue behind one another on the shared wire.
        var trips = firmware.RoundTripsMsSince(exchangesBefore);
        var allowed = Units.SecondsToMs(4 * _timing.StageJitterSeconds);
        if (trips.Count < 8 || allowed <= 0)
        {
            return 1;
        }

        // A reply held up far beyond the spread (a device busy a moment, a fault) is a doubt for the checks to catch, not a
        // spread to time every edge by. Capped: far wider, the profile is wrong, not the margins.
        trips.Sort();
        var median = trips[trips.Count / 2];
        var spread = trips.Where(t => t <= median + (5 * allowed)).Max() - trips[0];
        return spread <= allowed ? 1 : Math.Min(MaxLatencyScale, 2 * spread / allowed);
    }
}

/// <summary>What preflight found and did, which the run starts from.</summary>
/// <param name="Identity">Both axes' and the gate's identities.</param>
/// <param name="GateVouchesForCut">False when a resumed run counted on the gate's watchdog that did not trip: the gate was restarted since.</param>
/// <param name="ResumeX">Where in its burn run a resumed run starts (microsteps), or null to burn the run again from its start.</param>
/// <param name="Homed">Whether preflight homed the axes.</param>
/// <param name="X">The X axis' position after homing, microsteps.</param>
/// <param name="Y">The Y axis' position after homing, microsteps.</param>
/// <param name="LatencyScale">The latency spread the run assumes, in times the profile's (1, or wider for a timed raster).</param>
/// <param name="Timing">The timing the run times itself with: the plan's, or one for the wider spread.</param>
/// <param name="ScheduledBursts">Whether the gate takes scheduled bursts (CAPS? lists AFTER) and the run is a timed raster: its switch-ons are then timed by the gate.</param>
internal sealed record PreflightOutcome(MachineIdentity Identity, bool GateVouchesForCut, long? ResumeX, bool Homed, long X, long Y, double LatencyScale, TimedSwitching? Timing, bool ScheduledBursts);
