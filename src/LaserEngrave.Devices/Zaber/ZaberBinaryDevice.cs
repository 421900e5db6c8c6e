using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Motion;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Devices.Zaber;

/// <summary>One Zaber T-series axis on a <see cref="ZaberConnection"/>, speaking the binary protocol.</summary>
/// <remarks>
/// Moves reply on completion, so each move's timeout follows from its distance and the speed and acceleration the
/// device holds: they are read at <see cref="IdentifyAsync"/> (or before the first move) and remembered whenever
/// they are set. Positions and distances are microsteps.
/// </remarks>
public sealed class ZaberBinaryDevice : IStageAxis, IAxisFirmware
{
    /// <summary>Device Mode bit 0: the device does not reply to most commands.</summary>
    public const int AutoReplyDisabledBit = 0x01;

    /// <summary>Device Mode bit 7: the position is valid (homed, or set with Set Current Position).</summary>
    public const int HomeStatusBit = 0x80;

    private readonly Lock _state = new();
    private int? _speedData;
    private int? _accelerationData;
    private int? _homeSpeedData;
    private int? _deviceMode;
    private long? _maximumPosition;
    private long? _position;
    private int? _firmware;

    public ZaberBinaryDevice(ZaberConnection connection, byte deviceNumber, string? label = null)
    {
        ArgumentNullException.ThrowIfNull(connection);
        if (deviceNumber == 0 || deviceNumber == 255)
        {
            throw new ArgumentOutOfRangeException(nameof(deviceNumber), $"{connection.PortName}: a Zaber device number is 1..254 (got {deviceNumber})");
        }

        Connection = connection;
        DeviceNumber = deviceNumber;
        Label = label;
        connection.SetDeviceLabel(deviceNumber, label);
        connection.UnsolicitedReply += OnUnsolicitedReply;
    }

    /// <summary>Reply-only frames of this device: Move Tracking, Limit Active, Manual Move Tracking, stray errors.</summary>
    public event EventHandler<ZaberReplyEventArgs>? UnsolicitedReply;

    public ZaberConnection Connection { get; }

    public byte DeviceNumber { get; private set; }

    /// <summary>Role in messages, such as "X".</summary>
    public string? Label { get; }

    /// <summary>"device 1 (X)".</summary>
    public string Description => Connection.DescribeDevice(DeviceNumber);

    /// <summary>Target Speed data last read or set (x 9.375 microsteps/s), null until known.</summary>
    public int? SpeedData => Read(() => _speedData);

    /// <summary>Acceleration data last read or set (x 11250 microsteps/s²), null until known.</summary>
    public int? AccelerationData => Read(() => _accelerationData);

    /// <summary>Home Speed data if the firmware has it (5.20 and later).</summary>
    public int? HomeSpeedData => Read(() => _homeSpeedData);

    public int? DeviceMode => Read(() => _deviceMode);

    public long? MaximumPosition => Read(() => _maximumPosition);

    /// <summary>Firmware version x 100 once read (<see cref="IdentifyAsync"/>, <see cref="ReturnFirmwareVersionAsync"/>); null until then.</summary>
    public int? FirmwareVersion => Read(() => _firmware);

    /// <summary>Position from the last reply that carried one; null when unknown (after a timeout, Reset, constant-speed move).</summary>
    public long? LastKnownPosition => Read(() => _position);

    public async Task<long> HomeAsync(CancellationToken cancellationToken)
    {
        await EnsureMotionSettingsAsync(cancellationToken);
        var (speed, homeSpeed, acceleration, maximum) = Read(() => (_speedData!.Value, _homeSpeedData, _accelerationData!.Value, _maximumPosition!.Value));

        // Homing may cross the whole travel and back off the sensor, at the home speed where the firmware has one.
        var slowest = homeSpeed is { } h && h > 0 ? Math.Min(h, speed) : speed;
        var reply = await RequestAsync(ZaberCommand.Home, 0, MoveTimeout(maximum + 1, slowest, acceleration), cancellationToken);
        Write(() =>
        {
            _position = reply.Data;
            _deviceMode = _deviceMode is { } mode ? mode | HomeStatusBit : null;
        });
        return reply.Data;
    }

    public async Task<long> MoveAbsoluteAsync(long position, CancellationToken cancellationToken)
    {
        var target = ToData(position, nameof(position));
        await EnsureMotionSettingsAsync(cancellationToken);
        var (speed, acceleration, maximum, from) = Read(() => (_speedData!.Value, _accelerationData!.Value, _maximumPosition!.Value, _position));
        var distance = from is { } start ? Math.Abs(position - start) : Math.Max(Math.Abs(position), Math.Abs(maximum - position));
        return await MoveAsync(ZaberCommand.MoveAbsolute, target, MoveTimeout(distance, speed, acceleration), cancellationToken);
    }

    /// <summary>
    /// Moves to an absolute position, sent to arrive after the device's current move has ended (its reply may still be on
    /// the way): that move is not counted as pre-empted, and each waits for its own reply.
    /// </summary>
    public async Task<long> MoveAbsoluteAfterAsync(long position, CancellationToken cancellationToken)
    {
        var target = ToData(position, nameof(position));
        await EnsureMotionSettingsAsync(cancellationToken);
        var (speed, acceleration, maximum) = Read(() => (_speedData!.Value, _accelerationData!.Value, _maximumPosition!.Value));
        var distance = Math.Max(Math.Abs(position), Math.Abs(maximum - position));
        try
        {
            var request = new ZaberFrame(DeviceNumber, ZaberCommand.MoveAbsolute, target);
            var reply = await Connection.RequestCoreAsync(request, MoveTimeout(distance, speed, acceleration), holdLine: false, resynchroniseOnTimeout: true, cancellationToken, preempts: false);
            Write(() => _position = reply.Data);
            return reply.Data;
        }
        catch (Exception ex) when (ex is DeviceTimeoutException or ZaberInterruptedException or OperationCanceledException)
        {
            Write(() => _position = null);
            throw;
        }
    }

    public async Task<long> MoveRelativeAsync(long distance, CancellationToken cancellationToken)
    {
        var data = ToData(distance, nameof(distance));
        await EnsureMotionSettingsAsync(cancellationToken);
        var (speed, acceleration) = Read(() => (_speedData!.Value, _accelerationData!.Value));
        return await MoveAsync(ZaberCommand.MoveRelative, data, MoveTimeout(Math.Abs(distance), speed, acceleration), cancellationToken);
    }

    /// <summary>Starts moving at a signed speed (data x 9.375 microsteps/s); replies at once with the speed.</summary>
    /// <remarks>The move ends at a limit with a Limit Active frame (see <see cref="UnsolicitedReply"/>) or with Stop.</remarks>
    public async Task<int> MoveAtConstantSpeedAsync(int speedData, CancellationToken cancellationToken)
    {
        Write(() => _position = null);
        var reply = await RequestAsync(ZaberCommand.MoveAtConstantSpeed, speedData, Connection.Options.CommandTimeout, cancellationToken);
        return reply.Data;
    }

    /// <summary>One of a stream of speed changes: an earlier command of this device still waiting for its reply is not replaced; replies come in order.</summary>
    public async Task<int> StreamSpeedAsync(int speedData, CancellationToken cancellationToken)
    {
        Write(() => _position = null);
        var request = new ZaberFrame(DeviceNumber, ZaberCommand.MoveAtConstantSpeed, speedData);
        var reply = await Connection.RequestCoreAsync(request, Connection.Options.CommandTimeout, holdLine: false, resynchroniseOnTimeout: true, cancellationToken, preempts: false);
        return reply.Data;
    }

    /// <summary>Stop at the end of a stream of speed changes, which it does not count as replaced.</summary>
    public async Task<long> StreamStopAsync(CancellationToken cancellationToken)
    {
        var (speed, acceleration) = Read(() => (_speedData ?? StageUnits.MaxSettingData, _accelerationData ?? 1));
        var decelerationS = StageUnits.SpeedMicrostepsPerS(Math.Max(speed, 1)) / StageUnits.AccelerationMicrostepsPerS2(acceleration);
        var timeout = Connection.Options.CommandTimeout + (TimeSpan.FromSeconds(decelerationS * Connection.Options.MoveTimeoutFactor) + Connection.Options.MoveTimeoutMargin);
        var request = new ZaberFrame(DeviceNumber, ZaberCommand.Stop, 0);
        var reply = await Connection.RequestCoreAsync(request, timeout, holdLine: false, resynchroniseOnTimeout: true, cancellationToken, preempts: false);
        Write(() => _position = reply.Data);
        return reply.Data;
    }

    public async Task<long> StopAsync(CancellationToken cancellationToken)
    {
        var (speed, acceleration) = Read(() => (_speedData ?? StageUnits.MaxSettingData, _accelerationData ?? 1));

        // Stop replies after decelerating from at most the target speed (or a constant speed up to the maximum).
        var decelerationS = StageUnits.SpeedMicrostepsPerS(Math.Max(speed, 1)) / StageUnits.AccelerationMicrostepsPerS2(acceleration);
        var timeout = Connection.Options.CommandTimeout + (TimeSpan.FromSeconds(decelerationS * Connection.Options.MoveTimeoutFactor) + Connection.Options.MoveTimeoutMargin);
        var reply = await RequestAsync(ZaberCommand.Stop, 0, timeout, cancellationToken);
        Write(() => _position = reply.Data);
        return reply.Data;
    }

    /// <summary>Return Current Position.</summary>
    public async Task<long> GetPositionAsync(CancellationToken cancellationToken)
    {
        var reply = await RequestAsync(ZaberCommand.ReturnCurrentPosition, 0, cancellationToken);
        Write(() => _position = reply.Data);
        return reply.Data;
    }

    /// <summary>
    /// Sets the speed the next Home runs at: Set Home Speed from firmware 5.20; before 5.20 the command does not exist
    /// (error 64) and Home runs at the Target Speed, so the Target Speed is set instead (docs/zaber-protocol.md, firmware).
    /// </summary>
    public async Task SetHomeSpeedAsync(int speedData, CancellationToken cancellationToken)
    {
        var firmware = Read(() => _firmware) ?? await ReturnFirmwareVersionAsync(cancellationToken);
        if (!ZaberFirmware.HasHomeSpeed(firmware))
        {
            await SetTargetSpeedAsync(speedData, cancellationToken);
            return;
        }

        var reply = await RequestAsync(ZaberCommand.SetHomeSpeed, speedData, cancellationToken);
        Write(() => _homeSpeedData = reply.Data);
    }

    public async Task SetTargetSpeedAsync(int speedData, CancellationToken cancellationToken)
    {
        var reply = await RequestAsync(ZaberCommand.SetTargetSpeed, speedData, cancellationToken);
        Write(() => _speedData = reply.Data);
    }

    public async Task SetAccelerationAsync(int accelerationData, CancellationToken cancellationToken)
    {
        var reply = await RequestAsync(ZaberCommand.SetAcceleration, accelerationData, cancellationToken);
        Write(() => _accelerationData = reply.Data);
    }

    /// <summary>Sets the Maximum Position (travel limit) in microsteps; returns the value the device took.</summary>
    /// <exception cref="DeviceException">Firmware 5.21 or 5.22 and a maximum below the current position, which that firmware refuses.</exception>
    public async Task<long> SetMaximumPositionAsync(long maximumPosition, CancellationToken cancellationToken)
    {
        if (Read(() => (_firmware, _position)) is ({ } firmware, { } position) && ZaberFirmware.KeepsMaximumAboveCurrent(firmware) && maximumPosition < position)
        {
            throw new DeviceException(
                $"{Connection.PortName}: {Description} has firmware {ZaberFirmware.Text(firmware)}, which cannot set the Maximum Position ({maximumPosition}) below the current position ({position}); move it below that first");
        }

        var reply = await RequestAsync(ZaberCommand.SetMaximumPosition, ToData(maximumPosition, nameof(maximumPosition)), cancellationToken);
        Write(() => _maximumPosition = reply.Data);
        return reply.Data;
    }

    /// <summary>Overwrites the position counter without moving (the device then counts as homed).</summary>
    public async Task<long> SetCurrentPositionAsync(long position, CancellationToken cancellationToken)
    {
        var reply = await RequestAsync(ZaberCommand.SetCurrentPosition, ToData(position, nameof(position)), cancellationToken);
        Write(() =>
        {
            _position = reply.Data;
            _deviceMode = _deviceMode is { } mode ? mode | HomeStatusBit : null;
        });
        return reply.Data;
    }

    public Task ClearAutoReplyDisabledAsync(CancellationToken cancellationToken) => SetDeviceModeAsync(0, AutoReplyDisabledBit, cancellationToken);

    public long RoundTripsRecorded => Connection.RoundTripsRecorded;

    public List<double> RoundTripsMsSince(long since) =>
        Connection.RecentRoundTripsMs.TakeLast((int)Math.Min(Connection.RoundTripsRecorded - since, ZaberConnection.RoundTripsKept)).ToList();

    /// <summary>Sets and clears Device Mode bits, keeping the others: Set Device Mode overwrites the whole word, so
    /// the current word is read first (Return Setting 40).</summary>
    /// <returns>The Device Mode the device holds afterwards.</returns>
    public async Task<int> SetDeviceModeAsync(int setBits, int clearBits, CancellationToken cancellationToken)
    {
        var current = await ReturnSettingAsync(ZaberCommand.SetDeviceMode, cancellationToken);
        var wanted = (current | setBits) & ~clearBits;
        if (wanted == current)
        {
            return current;
        }

        var set = new ZaberFrame(DeviceNumber, ZaberCommand.SetDeviceMode, wanted);
        if (((current | wanted) & AutoReplyDisabledBit) != 0)
        {
            // Whether a device with auto-reply disabled (before or after) answers Set Device Mode is not documented:
            // send it, then read the word back, which such a device always answers.
            await Connection.SendAsync(set, cancellationToken);
        }
        else
        {
            await Connection.RequestAsync(set, cancellationToken);
        }

        var now = await ReturnSettingAsync(ZaberCommand.SetDeviceMode, cancellationToken);
        if (now != wanted)
        {
            throw new DeviceException(
                $"{Connection.PortName}: {Description} kept Device Mode 0x{now:X} after Set Device Mode 0x{wanted:X}");
        }

        return now;
    }

    /// <summary>Return Setting: the value of a "Set ..." command's setting (the reply carries the setting's number).</summary>
    public async Task<int> ReturnSettingAsync(ZaberCommand setting, CancellationToken cancellationToken)
    {
        var reply = await RequestAsync(ZaberCommand.ReturnSetting, (byte)setting, cancellationToken);
        Remember(setting, reply.Data);
        return reply.Data;
    }

    public async Task<int> ReturnDeviceIdAsync(CancellationToken cancellationToken) =>
        (await RequestAsync(ZaberCommand.ReturnDeviceId, 0, cancellationToken)).Data;

    /// <summary>Firmware version x 100 (502 = 5.02).</summary>
    public async Task<int> ReturnFirmwareVersionAsync(CancellationToken cancellationToken)
    {
        var firmware = (await RequestAsync(ZaberCommand.ReturnFirmwareVersion, 0, cancellationToken)).Data;
        Write(() => _firmware = firmware);
        return firmware;
    }

    /// <summary>
    /// A round trip of one frame each way that changes nothing: Echo Data where the firmware has it (5.04 on), else Return
    /// Firmware Version (also one frame each way, and answered in every 5.xx).
    /// </summary>
    public async Task PingAsync(int data, CancellationToken cancellationToken)
    {
        var firmware = Read(() => _firmware) ?? await ReturnFirmwareVersionAsync(cancellationToken);
        if (!ZaberFirmware.HasEchoData(firmware))
        {
            await ReturnFirmwareVersionAsync(cancellationToken);
            return;
        }

        var echoed = await EchoAsync(data, cancellationToken);
        if (echoed != data)
        {
            throw new DeviceException($"{Connection.PortName}: {Description} echoed {echoed} for Echo Data {data}; the line is garbled");
        }
    }

    /// <summary>Echo Data: the device sends <paramref name="data"/> back.</summary>
    public async Task<int> EchoAsync(int data, CancellationToken cancellationToken) =>
        (await RequestAsync(ZaberCommand.EchoData, data, cancellationToken)).Data;

    /// <summary>Gives this device a new number (1..254, stored in the device); nothing else is sent until it replies.</summary>
    public async Task RenumberAsync(byte newNumber, CancellationToken cancellationToken)
    {
        if (newNumber == 0 || newNumber == 255)
        {
            throw new ArgumentOutOfRangeException(nameof(newNumber), $"{Connection.PortName}: a Zaber device number is 1..254 (got {newNumber})");
        }

        var request = new ZaberFrame(DeviceNumber, ZaberCommand.Renumber, newNumber);
        await Connection.RequestCoreAsync(request, Connection.Options.RenumberTimeout, holdLine: true, resynchroniseOnTimeout: true, cancellationToken);
        DeviceNumber = newNumber;
        Connection.SetDeviceLabel(newNumber, Label);
    }

    /// <summary>Reset: like a power cycle (no reply); the position is lost and the device is no longer homed.</summary>
    public async Task ResetAsync(CancellationToken cancellationToken)
    {
        await Connection.SendAsync(new ZaberFrame(DeviceNumber, ZaberCommand.Reset, 0), cancellationToken);
        Write(() =>
        {
            _position = null;
            _deviceMode = _deviceMode is { } mode ? mode & ~HomeStatusBit : null;
        });
    }

    /// <summary>Reads device ID, firmware, Device Mode, Maximum Position, speed, acceleration, home speed and position.</summary>
    public async Task<AxisIdentity> IdentifyAsync(CancellationToken cancellationToken)
    {
        var deviceId = await ReturnDeviceIdAsync(cancellationToken);
        var firmware = await ReturnFirmwareVersionAsync(cancellationToken);
        var mode = await ReturnSettingAsync(ZaberCommand.SetDeviceMode, cancellationToken);
        await ReadMotionSettingsAsync(cancellationToken);
        await GetPositionAsync(cancellationToken);
        return new AxisIdentity(DeviceNumber, deviceId, firmware, mode, MaximumPosition ?? 0);
    }

    /// <summary>The timeout of a move over <paramref name="distance"/> microsteps at the given device data.</summary>
    internal TimeSpan MoveTimeout(long distance, int speedData, int accelerationData)
    {
        var options = Connection.Options;
        if (speedData <= 0)
        {
            // The device refuses a move at speed 0 straight away.
            return options.CommandTimeout;
        }

        var profile = new TrapezoidProfile(distance, StageUnits.SpeedMicrostepsPerS(speedData), StageUnits.AccelerationMicrostepsPerS2(accelerationData));
        return TimeSpan.FromSeconds(profile.Duration * options.MoveTimeoutFactor) + options.MoveTimeoutMargin;
    }

    private static int ToData(long value, string name) =>
        value is < int.MinValue or > int.MaxValue
            ? throw new ArgumentOutOfRangeException(name, value, "a Zaber value must fit in 32 bits")
            : (int)value;

    private async Task ReadMotionSettingsAsync(CancellationToken cancellationToken)
    {
        await ReturnSettingAsync(ZaberCommand.SetTargetSpeed, cancellationToken);
        await ReturnSettingAsync(ZaberCommand.SetAcceleration, cancellationToken);
        await ReturnSettingAsync(ZaberCommand.SetMaximumPosition, cancellationToken);
        if (Read(() => _firmware) is { } firmware && !ZaberFirmware.HasHomeSpeed(firmware))
        {
            // Firmware before 5.20 has no Home Speed setting and homes at the target speed: nothing to ask.
            Write(() => _homeSpeedData = null);
            return;
        }

        try
        {
            await ReturnSettingAsync(ZaberCommand.SetHomeSpeed, cancellationToken);
        }
        catch (ZaberException)
        {
            // Firmware before 5.20 has no Home Speed setting and homes at the target speed.
            Write(() => _homeSpeedData = null);
        }
    }

    private async Task EnsureMotionSettingsAsync(CancellationToken cancellationToken)
    {
        if (Read(() => _speedData is null || _accelerationData is null || _maximumPosition is null))
        {
            await ReadMotionSettingsAsync(cancellationToken);
        }
    }

    private async Task<long> MoveAsync(ZaberCommand command, int data, TimeSpan timeout, CancellationToken cancellationToken)
    {
        try
        {
            var reply = await RequestAsync(command, data, timeout, cancellationToken);
            Write(() => _position = reply.Data);
            return reply.Data;
        }
        catch (Exception ex) when (ex is DeviceTimeoutException or ZaberInterruptedException or OperationCanceledException)
        {
            // The axis may have stopped anywhere.
            Write(() => _position = null);
            throw;
        }
    }

    private Task<ZaberFrame> RequestAsync(ZaberCommand command, int data, CancellationToken cancellationToken) =>
        Connection.RequestAsync(new ZaberFrame(DeviceNumber, command, data), cancellationToken);

    private Task<ZaberFrame> RequestAsync(ZaberCommand command, int data, TimeSpan timeout, CancellationToken cancellationToken) =>
        Connection.RequestAsync(new ZaberFrame(DeviceNumber, command, data), timeout, cancellationToken);

    private void Remember(ZaberCommand setting, int value) => Write(() =>
    {
        switch (setting)
        {
            case ZaberCommand.SetTargetSpeed:
                _speedData = value;
                break;
            case ZaberCommand.SetAcceleration:
                _accelerationData = value;
                break;
            case ZaberCommand.SetHomeSpeed:
                _homeSpeedData = value;
                break;
            case ZaberCommand.SetMaximumPosition:
                _maximumPosition = value;
                break;
            case ZaberCommand.SetDeviceMode:
                _deviceMode = value;
                break;
            case ZaberCommand.SetCurrentPosition:
                _position = value;
                break;
        }
    });

    private void OnUnsolicitedReply(object? sender, ZaberReplyEventArgs e)
    {
        if (e.Reply.Device != DeviceNumber)
        {
            return;
        }

        if (e.Reply.Command is ZaberCommand.LimitActive)
        {
            Write(() => _position = e.Reply.Data);
        }

        UnsolicitedReply?.Invoke(this, e);
    }

    private T Read<T>(Func<T> read)
    {
        lock (_state)
        {
            return read();
        }
    }

    private void Write(Action write)
    {
        lock (_state)
        {
            write();
        }
    }
}
