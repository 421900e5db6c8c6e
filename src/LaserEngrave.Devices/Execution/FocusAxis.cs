using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.Devices.Execution;

/// <summary>Moves the focus (Z) axis between the jobs of a run: laser off first, then the move, awaited to its reply.</summary>
/// <remarks>
/// Called only between jobs, when the last job's moves have replied (the X-Y stage stands still) and its session has left
/// the laser off; the laser is switched off again, acknowledged, before Z moves, so nothing can fire while the focus
/// changes. The first move identifies the axis, sets its speed and acceleration from the profile, and homes it unless it
/// is homed. Positions are absolute microsteps from <see cref="ZAxisProfile.MicrostepsAt"/>, validated by the plan.
/// </remarks>
public sealed class FocusAxis
{
    private readonly IStageAxis _axis;
    private readonly ILaserGate _gate;
    private readonly ZAxisProfile _profile;
    private readonly int _speedData;
    private readonly int _accelerationData;
    private bool _prepared;

    public FocusAxis(IStage stage, ILaserGate gate, MachineProfile profile)
    {
        ArgumentNullException.ThrowIfNull(stage);
        ArgumentNullException.ThrowIfNull(gate);
        ArgumentNullException.ThrowIfNull(profile);
        _profile = profile.Z ?? throw new ArgumentException("the machine profile has no Z axis", nameof(profile));
        _axis = stage.Z ?? throw new PreflightException($"the machine profile has a Z axis (device {_profile.DeviceNumber}) but the stage offers none");
        _gate = gate;
        _speedData = _profile.SpeedData;
        _accelerationData = _profile.AccelerationData(profile.AccelerationMmPerS2);
    }

    /// <summary>Laser off, then Z stopped: an abort while Z moves (the move under way ends with <see cref="Zaber.ZaberInterruptedException"/>). Never throws.</summary>
    public async Task StopAsync()
    {
        foreach (var step in new Func<Task>[] { () => _gate.OffAsync(CancellationToken.None), () => _axis.StopAsync(CancellationToken.None) })
        {
            try
            {
                await step();
            }
            catch (DeviceException)
            {
                // The other step still runs: a gate that does not answer must not keep Z moving, nor the reverse.
            }
        }
    }

    /// <summary>Laser off (acknowledged), then Z to <paramref name="microsteps"/>, awaited; returns where the device says it arrived.</summary>
    /// <exception cref="DeviceException">The axis did not arrive where it was sent, or a device failed.</exception>
    public async Task<long> MoveToAsync(long microsteps, CancellationToken cancellationToken)
    {
        await _gate.OffAsync(cancellationToken);
        if (!_prepared)
        {
            var identity = await _axis.IdentifyAsync(cancellationToken);
            await _axis.SetAccelerationAsync(_accelerationData, cancellationToken);
            await _axis.SetTargetSpeedAsync(_speedData, cancellationToken);
            if (!identity.IsHomed)
            {
                await _axis.SetHomeSpeedAsync(_speedData, cancellationToken);
                await _axis.HomeAsync(cancellationToken);
            }

            _prepared = true;
        }

        long reached;
        try
        {
            reached = await _axis.MoveAbsoluteAsync(microsteps, cancellationToken);
        }
        catch (OperationCanceledException)
        {
            // The wait was given up; the axis must not go on moving on its own.
            await _axis.StopAsync(CancellationToken.None);
            throw;
        }

        if (reached != microsteps)
        {
            throw new DeviceException($"the Z axis (device {_axis.DeviceNumber}) arrived at {reached} microsteps, not at {microsteps}");
        }

        return reached;
    }
}
