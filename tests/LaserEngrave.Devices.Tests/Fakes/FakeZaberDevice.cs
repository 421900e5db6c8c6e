using LaserEngrave.Wire.Zaber;


namespace LaserEngrave.Devices.Tests.Fakes;

/// <summary>A minimal Zaber T-series device for host tests: replies at once, range-checks moves, keeps settings.</summary>
/// <remarks>Deliberately simple (no motion time, no gap rule): the real device model is the simulator's job.</remarks>
public sealed class FakeZaberDevice
{
    private static readonly HashSet<ZaberCommand> AnsweredWithAutoReplyDisabled =
        [ZaberCommand.Renumber, ZaberCommand.ReturnDeviceId, ZaberCommand.ReturnFirmwareVersion, ZaberCommand.ReturnSetting,
         ZaberCommand.ReturnStatus, ZaberCommand.EchoData, ZaberCommand.ReturnCurrentPosition];

    public FakeZaberDevice(byte number)
    {
        Number = number;
    }

    public byte Number { get; set; }

    public int DeviceId { get; set; } = 6213;

    public int Firmware { get; set; } = 523;

    public int Mode { get; set; }

    public long Position { get; set; } = 604724;

    public Dictionary<byte, int> Settings { get; } = new()
    {
        [(byte)ZaberCommand.SetTargetSpeed] = 2000,
        [(byte)ZaberCommand.SetAcceleration] = 100,
        [(byte)ZaberCommand.SetMaximumPosition] = 604724,
        [(byte)ZaberCommand.SetHomeSpeed] = 2000,
    };

    public int SpeedData => Settings[(byte)ZaberCommand.SetTargetSpeed];

    public int AccelerationData => Settings[(byte)ZaberCommand.SetAcceleration];

    public long MaximumPosition => Settings[(byte)ZaberCommand.SetMaximumPosition];

    /// <summary>What the device answers to <paramref name="command"/> (already addressed to it or to all).</summary>
    public IEnumerable<ZaberFrame> Handle(ZaberFrame command)
    {
        var reply = Execute(command);
        if (reply is not { } frame)
        {
            return [];
        }

        var autoReplyDisabled = (Mode & 1) != 0;
        return autoReplyDisabled && frame.Command != ZaberCommand.Error && !AnsweredWithAutoReplyDisabled.Contains(command.Command) ? [] : [frame];
    }

    private ZaberFrame? Execute(ZaberFrame command)
    {
        var data = command.Data;
        switch (command.Command)
        {
            case ZaberCommand.Reset:
                Mode &= ~0x80;
                return null;
            case ZaberCommand.Home:
                Position = 0;
                Mode |= 0x80;
                return Reply(ZaberCommand.Home, 0);
            case ZaberCommand.Renumber:
                Number = (byte)data;
                return Reply(ZaberCommand.Renumber, data);
            case ZaberCommand.MoveAbsolute:
                if (data < 0 || data > MaximumPosition)
                {
                    return Reply(ZaberCommand.Error, ZaberErrorCodes.MoveAbsoluteInvalid);
                }

                Position = data;
                return Reply(ZaberCommand.MoveAbsolute, data);
            case ZaberCommand.MoveRelative:
                if (Position + data < 0 || Position + data > MaximumPosition)
                {
                    return Reply(ZaberCommand.Error, ZaberErrorCodes.MoveRelativeInvalid);
                }

                Position += data;
                return Reply(ZaberCommand.MoveRelative, (int)Position);
            case ZaberCommand.MoveAtConstantSpeed:
                return Reply(ZaberCommand.MoveAtConstantSpeed, data);
            case ZaberCommand.Stop:
                return Reply(ZaberCommand.Stop, (int)Position);
            case ZaberCommand.SetDeviceMode:
                Mode = data;
                return Reply(ZaberCommand.SetDeviceMode, data);
            case ZaberCommand.SetCurrentPosition:
                Position = data;
                Mode |= 0x80;
                return Reply(ZaberCommand.SetCurrentPosition, data);
            case ZaberCommand.SetTargetSpeed or ZaberCommand.SetAcceleration or ZaberCommand.SetHomeSpeed:
                if (data is < 0 or > 32767)
                {
                    return Reply(ZaberCommand.Error, (int)command.Command);
                }

                Settings[(byte)command.Command] = data;
                return Reply(command.Command, data);
            case ZaberCommand.SetMaximumPosition:
                Settings[(byte)command.Command] = data;
                return Reply(command.Command, data);
            case ZaberCommand.ReturnDeviceId:
                return Reply(ZaberCommand.ReturnDeviceId, DeviceId);
            case ZaberCommand.ReturnFirmwareVersion:
                return Reply(ZaberCommand.ReturnFirmwareVersion, Firmware);
            case ZaberCommand.ReturnSetting:
                return (ZaberCommand)(byte)data switch
                {
                    ZaberCommand.SetDeviceMode => Reply(ZaberCommand.SetDeviceMode, Mode),
                    ZaberCommand.SetCurrentPosition => Reply(ZaberCommand.SetCurrentPosition, (int)Position),
                    _ when Settings.TryGetValue((byte)data, out var value) => Reply((ZaberCommand)(byte)data, value),
                    _ => Reply(ZaberCommand.Error, ZaberErrorCodes.SettingInvalid),
                };
            case ZaberCommand.EchoData:
                return Reply(ZaberCommand.EchoData, data);
            case ZaberCommand.ReturnCurrentPosition:
                return Reply(ZaberCommand.ReturnCurrentPosition, (int)Position);
            default:
                return Reply(ZaberCommand.Error, ZaberErrorCodes.CommandInvalid);
        }
    }

    private ZaberFrame Reply(ZaberCommand command, int data) => new(Number, command, data);
}
