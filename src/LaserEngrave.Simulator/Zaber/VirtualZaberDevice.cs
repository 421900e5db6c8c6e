using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Motion;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Simulator.Zaber;

/// <summary>One simulated Zaber T-series linear actuator (binary protocol, firmware 5.xx).</summary>
/// <remarks>
/// Follows /work/shared/reference/zaber-binary.md §7. Where the reference is silent this device chooses, and says so:
/// error replies are sent even with auto-reply disabled; Move Absolute/Relative/At Constant Speed while homing are
/// refused with 255 (Busy); Set Current Position while moving is refused with 255; a pre-empted move does not reply
/// unless <see cref="SimulatorOptions.ReplyToPreemptedMoves"/>; Device Mode bits 6 (message IDs), 8, 10, 12, 13 and
/// 16 and up are refused with 40; Renumber to a device takes effect at once and replies after
/// <see cref="SimulatorOptions.RenumberTime"/>. All state is guarded by the chain's lock.
/// </remarks>
public sealed class VirtualZaberDevice
{
    /// <summary>Device Mode bit 0: replies to commands other than Echo, Renumber and Return… are not sent.</summary>
    public const int AutoReplyDisabledBit = 1 << 0;

    /// <summary>Device Mode bit 4: Move Tracking (command 8) replies while moving.</summary>
    public const int MoveTrackingBit = 1 << 4;

    /// <summary>Device Mode bit 7: homed (the position is valid).</summary>
    public const int HomedBit = 1 << 7;

    /// <summary>Device Mode bits a T-LA accepts: 0-5, 7, 9, 11, 14, 15.</summary>
    public const int ValidModeBits = 0b1100_1010_1011_1111;

    /// <summary>Largest Maximum Position (24 bits).</summary>
    public const int MaxMaximumPosition = 16_777_215;

    private readonly VirtualZaberChain _chain;
    private readonly SimulatorOptions _options;
    private int _activeCommand;
    private long _target;
    private double _activeSpeed;
    private long _generation;
    private ITimer? _completion;
    private ITimer? _tracking;

    internal VirtualZaberDevice(VirtualZaberChain chain, AxisName axis, int chainIndex, byte number, long maximumPosition, AxisTrajectory trajectory, SimulatorOptions options)
    {
        _chain = chain;
        _options = options;
        Axis = axis;
        ChainIndex = chainIndex;
        Number = number;
        MaximumPosition = maximumPosition;
        Trajectory = trajectory;
        DeviceMode = options.DeviceMode & ~HomedBit;
        TargetSpeedData = options.TargetSpeedData;
        HomeSpeedData = options.HomeSpeedData;
        AccelerationData = options.AccelerationData;
    }

    public AxisName Axis { get; }

    /// <summary>Place on the daisy chain, 0 nearest the PC.</summary>
    public int ChainIndex { get; }

    /// <summary>Current device number (Renumber changes it).</summary>
    public byte Number { get; private set; }

    public int DeviceMode { get; private set; }

    public int TargetSpeedData { get; private set; }

    public int HomeSpeedData { get; private set; }

    public int AccelerationData { get; private set; }

    public long MaximumPosition { get; private set; }

    public bool IsHomed => (DeviceMode & HomedBit) != 0;

    /// <summary>Firmware version x 100 (<see cref="SimulatorOptions.FirmwareVersion"/>): what the device accepts follows it.</summary>
    public int FirmwareVersion => _options.FirmwareVersion;

    /// <summary>Set Home Speed (41) exists, and Home runs at it, from firmware 5.20.</summary>
    public bool HasHomeSpeed => FirmwareVersion >= 520;

    /// <summary>The axis' past and planned motion, microsteps over simulation seconds.</summary>
    public AxisTrajectory Trajectory { get; }

    /// <summary>Position now, in whole microsteps, as Return Current Position would answer.</summary>
    public long Position => Round(Trajectory.PositionAt(_chain.Clock.NowSeconds));

    /// <summary>Return Status now: 0 idle, 1 homing, 20/21 moving, 22 constant speed, 23 stopping.</summary>
    public int Status => _activeCommand;

    public bool IsMoving => _activeCommand != 0;

    private double Acceleration => StageUnits.AccelerationMicrostepsPerS2(AccelerationData);

    // Caller holds the chain's lock.
    internal void Handle(ZaberFrame frame, double now)
    {
        var command = (int)frame.Command;
        var data = frame.Data;
        switch (command)
        {
            case 0:
                PowerUp(now);
                break;
            case 1:
                // Home runs at the Home Speed from 5.20, at the Target Speed before (zaber-binary.md §6, [HSPD]).
                StartMove(command, 0, StageUnits.SpeedMicrostepsPerS(HasHomeSpeed ? HomeSpeedData : TargetSpeedData), now);
                break;
            case 2:
                Renumber(frame.Device == 0 ? ChainIndex + 1 : data, now);
                break;
            case 20 when _activeCommand == 1:
            case 21 when _activeCommand == 1:
            case 22 when _activeCommand == 1:
                Refuse(command, ZaberErrorCodes.Busy, now);
                break;
            case 20 or 21 when TargetSpeedData == 0:
                // A Target Speed of 0 (taken by firmware other than 5.21-5.22) makes the moves that use it fail ([TSPD]).
                Refuse(command, command, now);
                break;
            case 20:
                if (data < 0 || data > MaximumPosition)
                {
                    Refuse(command, ZaberErrorCodes.MoveAbsoluteInvalid, now);
                }
                else
                {
                    StartMove(command, data, StageUnits.SpeedMicrostepsPerS(TargetSpeedData), now);
                }

                break;
            case 21:
                var relativeTarget = Round(Trajectory.PositionAt(now)) + data;
                if (relativeTarget < 0 || relativeTarget > MaximumPosition)
                {
                    Refuse(command, ZaberErrorCodes.MoveRelativeInvalid, now);
                }
                else
                {
                    StartMove(command, relativeTarget, StageUnits.SpeedMicrostepsPerS(TargetSpeedData), now);
                }

                break;
            case 22:
                MoveAtConstantSpeed(data, now);
                break;
            case 23:
                Stop(command, now);
                break;
            case 40:
                SetSetting(command, data, (data & ~ValidModeBits) == 0, () => DeviceMode = data);
                if (IsMoving && _tracking is null && (DeviceMode & MoveTrackingBit) != 0)
                {
                    var generation = _generation;
                    _tracking = _chain.Clock.Every(_options.MoveTrackingPeriod, () => Track(generation));
                }

                break;
            case 41 when !HasHomeSpeed:
            case 55 when FirmwareVersion < 504:
                // Set Home Speed exists from 5.20 [HSPD], Echo Data from 5.04 [ECHO]: "command invalid for this firmware".
                Refuse(command, ZaberErrorCodes.CommandInvalid, now);
                break;
            case 41:
                SetSetting(command, data, data is >= 1 and <= StageUnits.MaxSettingData, () => HomeSpeedData = data);
                break;
            case 42:
                // 0 is a valid setting except on 5.21-5.22, which refuse it outright ([TSPD]); a move at 0 is refused.
                SetSetting(command, data, data is >= 0 and <= StageUnits.MaxSettingData && !(data == 0 && FirmwareVersion is 521 or 522), () => TargetSpeedData = data);
                if (_activeCommand is 20 or 21 && TargetSpeedData == data && data > 0)
                {
                    Replan(StageUnits.SpeedMicrostepsPerS(data), now);
                }

                break;
            case 43:
                SetSetting(command, data, data is >= 0 and <= StageUnits.MaxSettingData, () => AccelerationData = data);
                if (_activeCommand is 1 or 20 or 21 or 22 && AccelerationData == data)
                {
                    Replan(_activeSpeed, now);
                }

                break;
            case 44:
                // 5.21-5.22 cannot set the Maximum Position below the current position ([MAXP]).
                SetSetting(command, data, data is >= 1 and <= MaxMaximumPosition && !(FirmwareVersion is 521 or 522 && data < Round(Trajectory.PositionAt(now))), () => MaximumPosition = data);
                break;
            case 45 when IsMoving:
                Refuse(command, ZaberErrorCodes.Busy, now);
                break;
            case 45:
                SetSetting(command, data, data >= 0 && data <= MaximumPosition, () =>
                {
                    Trajectory.Replace(now, [MotionSegment.Hold(now, data)]);
                    DeviceMode |= HomedBit;
                });
                break;
            case 50:
                Reply(command, _options.DeviceId);
                break;
            case 51:
                Reply(command, FirmwareVersion);
                break;
            case 53:
                ReturnSetting(data, now);
                break;
            case 54:
                Reply(command, _activeCommand);
                break;
            case 55:
                Reply(command, data);
                break;
            case 60:
                Reply(command, (int)Round(Trajectory.PositionAt(now)));
                break;
            default:
                Refuse(command, ZaberErrorCodes.CommandInvalid, now);
                break;
        }
    }

    /// <summary>Answers <paramref name="command"/> with an error reply; nothing moves. Caller holds the chain's lock.</summary>
    internal void Refuse(int command, int code, double now)
    {
        if (command is 1 or 18 or 20 or 21 or 22)
        {
            _chain.Recorder.RecordRefusedMove(new RefusedMove(now, Axis, command, code));
        }

        _chain.Send(this, new ZaberFrame(Number, ZaberCommand.Error, code), solicited: true);
    }

    private static long Round(double microsteps) => (long)Math.Round(microsteps, MidpointRounding.AwayFromZero);

    private static bool AnswersWithAutoReplyDisabled(int command) => command is 2 or 50 or 51 or 53 or 54 or 55 or 60;

    private void Reply(int command, int data, bool solicited = true)
    {
        if (solicited && (DeviceMode & AutoReplyDisabledBit) != 0 && !AnswersWithAutoReplyDisabled(command))
        {
            return;
        }

        _chain.Send(this, new ZaberFrame(Number, (ZaberCommand)command, data), solicited);
    }

    private void SetSetting(int command, int data, bool valid, Action apply)
    {
        if (!valid)
        {
            Refuse(command, command, _chain.Clock.NowSeconds);
            return;
        }

        apply();
        Reply(command, data);
    }

    private void ReturnSetting(int setting, double now)
    {
        int? value = setting switch
        {
            40 => DeviceMode,
            41 when HasHomeSpeed => HomeSpeedData,
            42 => TargetSpeedData,
            43 => AccelerationData,
            44 => (int)MaximumPosition,
            45 => (int)Round(Trajectory.PositionAt(now)),
            _ => null,
        };
        if (value is { } v)
        {
            // Return Setting answers with the setting's own command number, and answers even with auto-reply disabled
            // (a Return command), so the reply is sent directly rather than through Reply's auto-reply check.
            _chain.Send(this, new ZaberFrame(Number, (ZaberCommand)setting, v), solicited: true);
        }
        else
        {
            Refuse(53, ZaberErrorCodes.SettingInvalid, now);
        }
    }

    private void PowerUp(double now)
    {
        EndMotion();
        // Settings are non-volatile and survive; the position is lost and reads as the maximum.
        Trajectory.Replace(now, [MotionSegment.Hold(now, MaximumPosition)]);
        DeviceMode &= ~HomedBit;
    }

    private void Renumber(int newNumber, double now)
    {
        if (newNumber is < 1 or > 254)
        {
            Refuse(2, 2, now);
            return;
        }

        Number = (byte)newNumber;
        var timer = default(ITimer);
        timer = _chain.Clock.At(now + _options.RenumberTime.TotalSeconds, () =>
        {
            lock (_chain.Lock)
            {
                Reply(2, _options.DeviceId);
            }

            timer?.Dispose();
        });
    }

    private void MoveAtConstantSpeed(int speedData, double now)
    {
        if (Math.Abs((long)speedData) > StageUnits.MaxSettingData)
        {
            Refuse(22, ZaberErrorCodes.VelocityInvalid, now);
            return;
        }

        Reply(22, speedData);
        if (speedData == 0)
        {
            // Commanding speed 0 ends the constant-speed move like a limit: it stops and sends Limit Active.
            Stop(22, now);
            return;
        }

        StartMove(22, speedData > 0 ? MaximumPosition : 0, StageUnits.SpeedMicrostepsPerS(Math.Abs(speedData)), now);
    }

    private void StartMove(int command, long target, double speed, double now)
    {
        Preempt(now);
        _activeCommand = command;
        _target = target;
        _activeSpeed = speed;
        var plan = MotionPlanner.Plan(now, Trajectory.PositionAt(now), Trajectory.VelocityAt(now), target, speed, Acceleration);
        Begin(plan, now);
    }

    private void Stop(int command, double now)
    {
        if (!IsMoving && command == 23)
        {
            Reply(23, (int)Round(Trajectory.PositionAt(now)));
            return;
        }

        Preempt(now);
        var plan = MotionPlanner.Stop(now, Trajectory.PositionAt(now), Trajectory.VelocityAt(now), Acceleration);
        _activeCommand = command;
        _target = Round(plan[^1].StartPosition);
        Begin(plan, now);
    }

    // A Set Target Speed or Set Acceleration during a move: the same target with the new settings.
    private void Replan(double speed, double now)
    {
        _activeSpeed = speed;
        var plan = MotionPlanner.Plan(now, Trajectory.PositionAt(now), Trajectory.VelocityAt(now), _target, speed, Acceleration);
        var command = _activeCommand;
        EndMotion();
        _activeCommand = command;
        Begin(plan, now);
    }

    private void Preempt(double now)
    {
        if (_activeCommand is 1 or 20 or 21 or 23 && _options.ReplyToPreemptedMoves)
        {
            Reply(_activeCommand, (int)Round(Trajectory.PositionAt(now)));
        }

        EndMotion();
    }

    private void Begin(List<MotionSegment> plan, double now)
    {
        Trajectory.Replace(now, plan);
        var generation = ++_generation;
        _completion = _chain.Clock.At(plan[^1].StartSeconds, () => Complete(generation));
        if ((DeviceMode & MoveTrackingBit) != 0)
        {
            _tracking = _chain.Clock.Every(_options.MoveTrackingPeriod, () => Track(generation));
        }
    }

    private void EndMotion()
    {
        _generation++;
        _completion?.Dispose();
        _tracking?.Dispose();
        _completion = null;
        _tracking = null;
        _activeCommand = 0;
    }

    private void Complete(long generation)
    {
        lock (_chain.Lock)
        {
            if (generation != _generation)
            {
                return;
            }

            var command = _activeCommand;
            var final = (int)_target;
            EndMotion();
            switch (command)
            {
                case 1:
                    DeviceMode |= HomedBit;
                    Reply(1, final);
                    break;
                case 22:
                    Reply((int)ZaberCommand.LimitActive, final, solicited: false);
                    break;
                default:
                    Reply(command, final);
                    break;
            }
        }
    }

    private void Track(long generation)
    {
        lock (_chain.Lock)
        {
            if (generation != _generation)
            {
                return;
            }

            if ((DeviceMode & MoveTrackingBit) != 0)
            {
                Reply((int)ZaberCommand.MoveTracking, (int)Round(Trajectory.PositionAt(_chain.Clock.NowSeconds)), solicited: false);
            }
        }
    }
}
