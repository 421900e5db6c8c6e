using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Motion;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Scheduling;
using LaserEngrave.Devices.Zaber;

namespace LaserEngrave.Devices.Execution;

/// <summary>Preflight: the gate and both axes identified and checked, the job against the machine, before anything moves or fires (docs/execution.md, "Preflight").</summary>
public sealed partial class RunExecutor
{
    private async Task<MachineIdentity> PreflightAsync(CancellationToken token)
    {
        CheckJob();
        string gateIdentity;
        try
        {
            gateIdentity = await OnceMoreAfterTimeoutAsync(() => Gate.IdentifyAsync(token));
            if (Options.ResumeFrom is { OffByGateWatchdog: true } && !(await Gate.GetStateAsync(token)).WatchdogTripped)
            {
                // The laser's switch-off time counted on the watchdog; a gate restarted since cannot vouch for it.
                _gateVouchesForCut = false;
            }

            await Gate.OffAsync(token);
            await Gate.SetWatchdogAsync(_profile.Gate.WatchdogMs, token);
        }
        catch (DeviceException ex)
        {
            throw new PreflightException($"the laser gate does not answer as it should: {ex.Message}", ex);
        }

        var exchangesBefore = (Stage.X as IAxisFirmware)?.RoundTripsRecorded ?? 0;
        var x = await IdentifyAxisAsync(Stage.X, "X", token);
        var y = await IdentifyAxisAsync(Stage.Y, "Y", token);
        CheckFirmware(x, "X");
        CheckFirmware(y, "Y");
        CheckReach(x, y);
        // A gate whose watchdog did not trip heard a command that switched the laser off: the cut at the fault's first OFF.
        _resumeX = _gateVouchesForCut ? Options.ResumeFrom?.ResumeXMicrosteps : Options.ResumeFrom?.OffResumeXMicrosteps;
        if (Options.ResumeFrom is { ResumeXMicrosteps: not null, ExpectedXMicrosteps: { } expected })
        {
            // The stage could not be asked when the run stopped: it must be found where its motion was taking it, or the
            // time the laser went off says nothing of where it burned, and the cut-off run is burned again from its start.
            try
            {
                if (!x.IsHomed || await Stage.X.GetPositionAsync(token) != expected)
                {
                    _resumeX = null;
                }
            }
            catch (DeviceException ex)
            {
                throw new PreflightException($"the X axis does not answer: {ex.Message}", ex);
            }
        }

        var homing = new List<Task<long>>();
        try
        {
            // Homing at the process' acceleration and travel speed, so it takes the time the estimate says, not the device's power-up settings'.
            foreach (var (axis, identity) in new[] { (Stage.X, x), (Stage.Y, y) })
            {
                if (Options.Home || !identity.IsHomed)
                {
                    await axis.SetAccelerationAsync(_accelerationData, token);
                    await axis.SetHomeSpeedAsync(_travelSpeedData, token);
                }
            }

            if (Options.Home || !x.IsHomed)
            {
                homing.Add(Stage.X.HomeAsync(token));
            }

            if (Options.Home || !y.IsHomed)
            {
                homing.Add(Stage.Y.HomeAsync(token));
            }

            await Task.WhenAll(homing);
            _homed = homing.Count > 0;
            _x = await Stage.X.GetPositionAsync(token);
            _y = await Stage.Y.GetPositionAsync(token);
        }
        catch (DeviceException ex)
        {
            throw new PreflightException($"homing failed: {ex.Message}", ex);
        }

        // Raster timed switching only: a drawing's schedule and a step-by-step run keep the profile's latencies.
        var scale = Math.Max(double.IsFinite(Options.LatencyScale) ? Math.Max(1, Options.LatencyScale) : 1, SpreadSeenScale(exchangesBefore));
        if (scale > 1 && _motion == Motion.Timed && Job!.Plan.Timing is { } planned)
        {
            _latencyScale = scale;

            // Guards, margins, run-ups and checks all follow from the latencies' spread: the run times itself with the wider one.
            var latency = _profile.Latency;
            _timing = TimedSwitching.For(_process, _profile with
            {
                Latency = latency with
                {
                    StageJitterMs = latency.StageJitterMs * _latencyScale,
                    GateJitterMs = latency.GateJitterMs * _latencyScale,
                    GateProcessingJitterMs = latency.GateProcessingJitterMs * _latencyScale,
                },
            }, planned.MicrostepUm);
        }

        return new MachineIdentity(x, y, gateIdentity);
    }

    private async Task<AxisIdentity> IdentifyAxisAsync(IStageAxis axis, string name, CancellationToken token)
    {
        AxisIdentity identity;
        try
        {
            identity = await OnceMoreAfterTimeoutAsync(() => axis.IdentifyAsync(token));
            if (identity.AutoReplyDisabled)
            {
                if (!Options.FixAutoReply || axis is not IAxisFirmware firmware)
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
        var drawing = _motion == Motion.Strokes;
        var timedRaster = _motion == Motion.Timed;
        var missing = ZaberFirmware.Missing(identity.FirmwareVersion, speedChangeMidMove: timedRaster, constantSpeed: drawing);
        if (missing.Count > 0)
        {
            var instead = timedRaster ? "; engrave it step by step (--strategy paper), which needs neither" : string.Empty;
            throw new PreflightException(
                $"the {name} axis (device {identity.DeviceNumber}) has firmware {identity.FirmwareText}, for which the Zaber manual does not vouch for {string.Join(" nor ", missing)}, which this job needs (T-series firmware 5.00-5.99 has it){instead}");
        }
    }

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

    /// <summary>Refuses a job that leaves the travel or asks for speeds the stage cannot run.</summary>
    private void CheckJob()
    {
        if (Drawing is { } drawing)
        {
            CheckDrawing(drawing);
        }
        else if (!Job!.Geometry.FitsTravel)
        {
            var outside = Job.Geometry.Warnings.FirstOrDefault(w => w.Kind == JobWarningKind.OutsideTravel);
            throw new PreflightException(outside?.Message ?? "the job does not fit the stage travel");
        }

        var strategy = Job?.Plan.Options.Strategy ?? PlanStrategy.Optimized;
        var microstepUm = Job?.Plan.Geometry.MicrostepUm ?? _timing!.MicrostepUm;
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
        if (Job?.EngraveProblem is { } tooShort)
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
        if (Drawing is { } drawing)
        {
            CheckDrawingReach(drawing, x, y);
            return;
        }

        var plan = Job!.Plan;
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
}
