namespace LaserEngrave.Devices.Abstractions;

/// <summary>One linear axis of the stage (a Zaber device), in microsteps.</summary>
/// <remarks>Moves complete when the device replies on arrival; every call has its own timeout.</remarks>
public interface IStageAxis
{
    /// <summary>Zaber device number of the axis.</summary>
    byte DeviceNumber { get; }

    /// <summary>Homes the axis; returns the final position (0).</summary>
    Task<long> HomeAsync(CancellationToken cancellationToken);

    /// <summary>Moves to an absolute position and waits for arrival; returns the final position.</summary>
    Task<long> MoveAbsoluteAsync(long position, CancellationToken cancellationToken);

    /// <summary>
    /// Moves to an absolute position, sent to arrive just after the axis' current move ends (its reply may still be on the
    /// way); returns the final position. Devices that cannot tell the two apart simply move.
    /// </summary>
    Task<long> MoveAbsoluteAfterAsync(long position, CancellationToken cancellationToken) => MoveAbsoluteAsync(position, cancellationToken);

    /// <summary>Moves by a signed distance and waits for arrival; returns the final position.</summary>
    Task<long> MoveRelativeAsync(long distance, CancellationToken cancellationToken);

    /// <summary>
    /// Starts moving (or changes speed while moving) at a signed speed, in device units (x 9.375 microsteps/s): the axis
    /// ramps to it at its acceleration; returns once the device has acknowledged it. Devices without it refuse.
    /// </summary>
    Task<int> MoveAtConstantSpeedAsync(int speedData, CancellationToken cancellationToken) =>
        throw new NotSupportedException($"axis {DeviceNumber} cannot move at a constant speed");

    /// <summary>
    /// As <see cref="MoveAtConstantSpeedAsync"/>, one of a stream of speed changes: the axis' earlier commands still
    /// waiting for their replies are not counted as replaced, so a reply that never comes is noticed.
    /// </summary>
    Task<int> StreamSpeedAsync(int speedData, CancellationToken cancellationToken) => MoveAtConstantSpeedAsync(speedData, cancellationToken);

    /// <summary>As <see cref="StopAsync"/>, at the end of a stream of speed changes (<see cref="StreamSpeedAsync"/>).</summary>
    Task<long> StreamStopAsync(CancellationToken cancellationToken) => StopAsync(cancellationToken);

    /// <summary>Decelerates to a stop; returns the position where it stopped.</summary>
    Task<long> StopAsync(CancellationToken cancellationToken);

    Task<long> GetPositionAsync(CancellationToken cancellationToken);

    /// <summary>Sets the target speed, in device units (x 9.375 microsteps/s).</summary>
    Task SetTargetSpeedAsync(int speedData, CancellationToken cancellationToken);

    /// <summary>Sets the speed of homing, in device units (x 9.375 microsteps/s); devices without the setting ignore it.</summary>
    Task SetHomeSpeedAsync(int speedData, CancellationToken cancellationToken) => Task.CompletedTask;

    /// <summary>Sets the acceleration, in device units (x 11250 microsteps/s²).</summary>
    Task SetAccelerationAsync(int accelerationData, CancellationToken cancellationToken);

    /// <summary>Reads the device type ID, firmware version and Device Mode.</summary>
    Task<AxisIdentity> IdentifyAsync(CancellationToken cancellationToken);
}

/// <summary>What a Zaber device says about itself.</summary>
/// <param name="DeviceNumber">Number on the chain.</param>
/// <param name="DeviceId">Device type ID (Return Device ID).</param>
/// <param name="FirmwareVersion">Firmware version x 100 (502 = 5.02).</param>
/// <param name="DeviceMode">Set Device Mode bits.</param>
/// <param name="MaximumPosition">Maximum Position setting, microsteps.</param>
public sealed record AxisIdentity(byte DeviceNumber, int DeviceId, int FirmwareVersion, int DeviceMode, long MaximumPosition)
{
    /// <summary>Bit 7 of the Device Mode: the position is valid because the axis was homed.</summary>
    public bool IsHomed => (DeviceMode & 0x80) != 0;

    /// <summary>Bit 0 of the Device Mode: the device does not reply to commands.</summary>
    public bool AutoReplyDisabled => (DeviceMode & 0x01) != 0;

    public string FirmwareText => $"{FirmwareVersion / 100}.{FirmwareVersion % 100:00}";
}

/// <summary>The two axes of the X-Y stage, and the focus axis when the machine has one.</summary>
public interface IStage
{
    IStageAxis X { get; }

    IStageAxis Y { get; }

    /// <summary>The focus (Z) axis; null on a two-axis machine.</summary>
    IStageAxis? Z => null;

    /// <summary>True while bytes that arrived from the stage are still on their way to the host's code (unread, or being handed on); false when the link cannot tell.</summary>
    /// <remarks>A reply whose time is up asks it: a host stalled after the reply arrived is late to read it, not the stage to send it.</remarks>
    bool IsReceiving => false;

    /// <summary>
    /// Completes when the command asked for last on the stage's line (the call that returned just before this is read)
    /// has been written, with the time its write completed as a timestamp of the machine's clock; null when it was never
    /// written or the link cannot tell.
    /// </summary>
    Task<long?> LineWritten => Task.FromResult<long?>(null);
}
