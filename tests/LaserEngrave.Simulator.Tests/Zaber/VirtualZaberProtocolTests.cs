using LaserEngrave.Core.Geometry;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Simulator.Tests.Zaber;

/// <summary>The chain's protocol rules, through raw 6-byte frames (zaber-binary.md §7).</summary>
public class VirtualZaberProtocolTests
{
    private static readonly long MaxPosition = MachineProfile.Default.X.TravelMicrosteps;

    [Fact(Timeout = 20_000)]
    public async Task PowerUp_PositionIsMaximumAndNotHomed()
    {
        await using var bench = MachineBench.Create();

        var position = await bench.RequestAsync(1, ZaberCommand.ReturnCurrentPosition, 0);
        var mode = await bench.RequestAsync(1, ZaberCommand.ReturnSetting, (int)ZaberCommand.SetDeviceMode);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, (int)MaxPosition), position);
        Assert.Equal(0, mode.Data & 0x80);
    }

    [Fact(Timeout = 20_000)]
    public async Task Echo_AnyData_ReturnedUnchanged()
    {
        await using var bench = MachineBench.Create();

        var reply = await bench.RequestAsync(2, ZaberCommand.EchoData, -123456789);

        Assert.Equal(new ZaberFrame(2, ZaberCommand.EchoData, -123456789), reply);
    }

    [Fact(Timeout = 20_000)]
    public async Task Echo_Reply_ArrivesAfterOneFrameEachWay()
    {
        await using var bench = MachineBench.Create();
        var sent = bench.Now;

        await bench.SendAsync(1, ZaberCommand.EchoData, 7);
        var (_, at) = await bench.ReceiveAsync();

        AssertTicks(2 * MachineBench.FrameTime, at - sent);
    }

    [Fact(Timeout = 20_000)]
    public async Task Echo_TwoFramesBackToBack_RepliesQueueOnTheWire()
    {
        await using var bench = MachineBench.Create();
        var sent = bench.Now;

        await bench.SendRawAsync([.. new ZaberFrame(1, ZaberCommand.EchoData, 1).ToBytes(), .. new ZaberFrame(2, ZaberCommand.EchoData, 2).ToBytes()]);
        var (first, firstAt) = await bench.ReceiveAsync();
        var (second, secondAt) = await bench.ReceiveAsync();

        Assert.Equal((1, 2), (first.Device, second.Device));
        AssertTicks(2 * MachineBench.FrameTime, firstAt - sent);
        AssertTicks(3 * MachineBench.FrameTime, secondAt - sent);
    }

    [Fact(Timeout = 20_000)]
    public async Task Broadcast_ReturnDeviceId_EveryDeviceAnswersWithItsOwnNumber()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { DeviceId = 4321 });

        await bench.SendAsync(0, ZaberCommand.ReturnDeviceId, 0);
        var first = (await bench.ReceiveAsync()).Frame;
        var second = (await bench.ReceiveAsync()).Frame;

        Assert.Equal(new ZaberFrame(1, ZaberCommand.ReturnDeviceId, 4321), first);
        Assert.Equal(new ZaberFrame(2, ZaberCommand.ReturnDeviceId, 4321), second);
        Assert.Null(await bench.TryReceiveAsync(TimeSpan.FromSeconds(1)));
    }

    [Fact(Timeout = 20_000)]
    public async Task Address_OneDevice_OnlyThatDeviceAnswers()
    {
        await using var bench = MachineBench.Create();

        var reply = await bench.RequestAsync(2, ZaberCommand.ReturnFirmwareVersion, 0);

        Assert.Equal(new ZaberFrame(2, ZaberCommand.ReturnFirmwareVersion, 523), reply);
        Assert.Null(await bench.TryReceiveAsync(TimeSpan.FromSeconds(1)));
    }

    [Fact(Timeout = 20_000)]
    public async Task Address_NumberNoDeviceHas_NoReply()
    {
        await using var bench = MachineBench.Create();

        await bench.SendAsync(3, ZaberCommand.EchoData, 1);

        Assert.Null(await bench.TryReceiveAsync(TimeSpan.FromSeconds(1)));
    }

    [Fact(Timeout = 20_000)]
    public async Task Address_ProfileNumbers_DevicesTakeThem()
    {
        var profile = MachineProfile.Default with
        {
            X = MachineProfile.Default.X with { DeviceNumber = 7 },
            Y = MachineProfile.Default.Y with { DeviceNumber = 9 },
        };
        await using var bench = MachineBench.Create(profile: profile);

        await bench.SendAsync(0, ZaberCommand.EchoData, 5);

        Assert.Equal(7, (await bench.ReceiveAsync()).Frame.Device);
        Assert.Equal(9, (await bench.ReceiveAsync()).Frame.Device);
    }

    [Fact(Timeout = 20_000)]
    public async Task PartialFrame_GapOver10Ms_IsDiscarded()
    {
        await using var bench = MachineBench.Create();
        var stray = new ZaberFrame(1, ZaberCommand.EchoData, 111).ToBytes();

        await bench.SendRawAsync(stray[..3]);
        await bench.WaitAsync(TimeSpan.FromMilliseconds(20));
        await bench.SendAsync(1, ZaberCommand.EchoData, 222);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.EchoData, 222), (await bench.ReceiveAsync()).Frame);
        Assert.Null(await bench.TryReceiveAsync(TimeSpan.FromSeconds(1)));
    }

    [Fact(Timeout = 20_000)]
    public async Task PartialFrame_GapUnder10Ms_IsCompleted()
    {
        await using var bench = MachineBench.Create();
        var frame = new ZaberFrame(2, ZaberCommand.EchoData, 333).ToBytes();

        await bench.SendRawAsync(frame[..2]);
        await bench.WaitAsync(TimeSpan.FromMilliseconds(5));
        await bench.SendRawAsync(frame[2..]);

        Assert.Equal(new ZaberFrame(2, ZaberCommand.EchoData, 333), (await bench.ReceiveAsync()).Frame);
    }

    [Fact(Timeout = 20_000)]
    public async Task PartialFrame_Garbage_YieldsAWellFormedWrongFrame()
    {
        await using var bench = MachineBench.Create();

        // One stray byte shifts the next frame: the device reads 6 bytes whatever they are (no sync byte, no checksum).
        await bench.SendRawAsync([1, .. new ZaberFrame(1, ZaberCommand.EchoData, 0).ToBytes()[..5]]);

        Assert.Equal(new ZaberFrame(1, (ZaberCommand)1, 0), (await bench.ReceiveAsync(TimeSpan.FromSeconds(60))).Frame with { Data = 0 });
    }

    [Theory(Timeout = 20_000)]
    [InlineData(99)]
    [InlineData(16)]
    [InlineData(8)]
    public async Task UnknownCommand_RepliesError64(int command)
    {
        await using var bench = MachineBench.Create();

        await bench.SendAsync(1, command, 0);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.Error, 64), (await bench.ReceiveAsync()).Frame);
    }

    [Theory(Timeout = 20_000)]
    [InlineData(-1)]
    [InlineData(int.MinValue)]
    public async Task MoveAbsolute_BelowZero_Error20AndNothingMoves(int target)
    {
        await using var bench = MachineBench.Create();

        var reply = await bench.RequestAsync(1, ZaberCommand.MoveAbsolute, target);
        var position = await bench.RequestAsync(1, ZaberCommand.ReturnCurrentPosition, 0);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.Error, 20), reply);
        Assert.Equal(MaxPosition, position.Data);
    }

    [Fact(Timeout = 20_000)]
    public async Task MoveAbsolute_AboveMaximum_Error20()
    {
        await using var bench = MachineBench.Create();

        var reply = await bench.RequestAsync(2, ZaberCommand.MoveAbsolute, (int)MaxPosition + 1);

        Assert.Equal(new ZaberFrame(2, ZaberCommand.Error, 20), reply);
    }

    [Fact(Timeout = 20_000)]
    public async Task MoveAbsolute_ToMaximum_IsAccepted()
    {
        await using var bench = MachineBench.Create();
        await bench.RequestAsync(1, ZaberCommand.SetCurrentPosition, 0);

        var reply = await bench.RequestAsync(1, ZaberCommand.MoveAbsolute, (int)MaxPosition);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.MoveAbsolute, (int)MaxPosition), reply);
    }

    [Fact(Timeout = 20_000)]
    public async Task MoveAbsolute_Reply_CarriesTheFinalPosition()
    {
        await using var bench = MachineBench.Create();

        var reply = await bench.RequestAsync(1, ZaberCommand.MoveAbsolute, 123_457);
        var position = await bench.RequestAsync(1, ZaberCommand.ReturnCurrentPosition, 0);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 123_457), reply);
        Assert.Equal(123_457, position.Data);
    }

    [Fact(Timeout = 20_000)]
    public async Task MoveRelative_InRange_RepliesWithCurrentPlusDistance()
    {
        await using var bench = MachineBench.Create();

        var reply = await bench.RequestAsync(2, ZaberCommand.MoveRelative, -1000);

        Assert.Equal(new ZaberFrame(2, ZaberCommand.MoveRelative, (int)MaxPosition - 1000), reply);
    }

    [Fact(Timeout = 20_000)]
    public async Task MoveRelative_PastMaximum_Error21()
    {
        await using var bench = MachineBench.Create();

        var reply = await bench.RequestAsync(2, ZaberCommand.MoveRelative, 1);

        Assert.Equal(new ZaberFrame(2, ZaberCommand.Error, 21), reply);
    }

    [Fact(Timeout = 20_000)]
    public async Task MoveRelative_BelowZero_Error21()
    {
        await using var bench = MachineBench.Create();

        var reply = await bench.RequestAsync(1, ZaberCommand.MoveRelative, -(int)MaxPosition - 1);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.Error, 21), reply);
    }

    [Fact(Timeout = 20_000)]
    public async Task Home_FromPowerUp_RepliesZeroAndSetsHomedBit()
    {
        await using var bench = MachineBench.Create();

        var reply = await bench.RequestAsync(1, ZaberCommand.Home, 0);
        var mode = await bench.RequestAsync(1, ZaberCommand.ReturnSetting, (int)ZaberCommand.SetDeviceMode);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.Home, 0), reply);
        Assert.Equal(0x80, mode.Data & 0x80);
        Assert.Equal(new ZaberFrame(1, ZaberCommand.SetDeviceMode, mode.Data), mode);
    }

    [Fact(Timeout = 20_000)]
    public async Task Home_DuringHoming_MoveIsRefusedBusy()
    {
        await using var bench = MachineBench.Create();

        await bench.SendAsync(1, ZaberCommand.Home, 0);
        var refused = await bench.RequestAsync(1, ZaberCommand.MoveAbsolute, 10);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.Error, 255), refused);
        Assert.Equal(new ZaberFrame(1, ZaberCommand.Home, 0), (await bench.ReceiveAsync()).Frame);
    }

    [Fact(Timeout = 20_000)]
    public async Task MoveAtConstantSpeed_RepliesAtOnceThenLimitActiveAtTheEnd()
    {
        await using var bench = MachineBench.Create();
        var sent = bench.Now;

        await bench.SendAsync(1, ZaberCommand.MoveAtConstantSpeed, -30000);
        var (first, firstAt) = await bench.ReceiveAsync();
        var (limit, limitAt) = await bench.ReceiveAsync();

        Assert.Equal(new ZaberFrame(1, ZaberCommand.MoveAtConstantSpeed, -30000), first);
        AssertTicks(2 * MachineBench.FrameTime, firstAt - sent);
        Assert.Equal(new ZaberFrame(1, ZaberCommand.LimitActive, 0), limit);
        Assert.True(limitAt - firstAt > TimeSpan.FromSeconds(1), $"the limit came {limitAt - firstAt} after the reply");
    }

    [Fact(Timeout = 20_000)]
    public async Task MoveAtConstantSpeed_SpeedZero_StopsWithLimitActive()
    {
        await using var bench = MachineBench.Create();
        await bench.SendAsync(1, ZaberCommand.MoveAtConstantSpeed, -2000);
        await bench.ReceiveAsync();
        await bench.WaitAsync(TimeSpan.FromSeconds(1));

        await bench.SendAsync(1, ZaberCommand.MoveAtConstantSpeed, 0);
        var ack = (await bench.ReceiveAsync()).Frame;
        var limit = (await bench.ReceiveAsync()).Frame;

        Assert.Equal(new ZaberFrame(1, ZaberCommand.MoveAtConstantSpeed, 0), ack);
        Assert.Equal(ZaberCommand.LimitActive, limit.Command);
        Assert.InRange(limit.Data, 1, MaxPosition - 1);
    }

    [Fact(Timeout = 20_000)]
    public async Task MoveAtConstantSpeed_OutOfRange_Error22()
    {
        await using var bench = MachineBench.Create();

        var reply = await bench.RequestAsync(1, ZaberCommand.MoveAtConstantSpeed, 40000);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.Error, 22), reply);
    }

    [Fact(Timeout = 20_000)]
    public async Task Stop_DuringMove_RepliesWhereItStoppedAndTheMoveNever()
    {
        await using var bench = MachineBench.Create();
        await bench.SendAsync(1, ZaberCommand.MoveAbsolute, 0);
        await bench.WaitAsync(TimeSpan.FromSeconds(2));

        var stop = await bench.RequestAsync(1, ZaberCommand.Stop, 0);
        var position = await bench.RequestAsync(1, ZaberCommand.ReturnCurrentPosition, 0);

        Assert.Equal(ZaberCommand.Stop, stop.Command);
        Assert.InRange(stop.Data, 1, MaxPosition - 1);
        Assert.Equal(stop.Data, position.Data);
        Assert.Null(await bench.TryReceiveAsync(TimeSpan.FromMinutes(2)));
    }

    [Fact(Timeout = 20_000)]
    public async Task Stop_Idle_RepliesCurrentPosition()
    {
        await using var bench = MachineBench.Create();

        var stop = await bench.RequestAsync(2, ZaberCommand.Stop, 0);

        Assert.Equal(new ZaberFrame(2, ZaberCommand.Stop, (int)MaxPosition), stop);
    }

    [Fact(Timeout = 20_000)]
    public async Task MoveAbsolute_NewMoveDuringMove_PreemptsAndOnlyTheNewOneReplies()
    {
        await using var bench = MachineBench.Create();
        await bench.SendAsync(1, ZaberCommand.MoveAbsolute, 0);
        await bench.WaitAsync(TimeSpan.FromSeconds(1));

        var reply = await bench.RequestAsync(1, ZaberCommand.MoveAbsolute, 500_000);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 500_000), reply);
        Assert.Null(await bench.TryReceiveAsync(TimeSpan.FromMinutes(2)));
    }

    [Fact(Timeout = 20_000)]
    public async Task MoveAbsolute_PreemptedWithReplyOption_OldMoveRepliesWhereItWas()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { ReplyToPreemptedMoves = true });
        await bench.SendAsync(1, ZaberCommand.MoveAbsolute, 0);
        await bench.WaitAsync(TimeSpan.FromSeconds(1));

        await bench.SendAsync(1, ZaberCommand.MoveAbsolute, 500_000);
        var old = (await bench.ReceiveAsync()).Frame;
        var reply = (await bench.ReceiveAsync()).Frame;

        Assert.Equal(ZaberCommand.MoveAbsolute, old.Command);
        Assert.InRange(old.Data, 1, MaxPosition - 1);
        Assert.Equal(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 500_000), reply);
    }

    [Theory(Timeout = 20_000)]
    [InlineData(ZaberCommand.SetTargetSpeed, -1)]
    [InlineData(ZaberCommand.SetTargetSpeed, 32768)]
    [InlineData(ZaberCommand.SetHomeSpeed, 0)]
    [InlineData(ZaberCommand.SetAcceleration, -1)]
    [InlineData(ZaberCommand.SetAcceleration, 32768)]
    [InlineData(ZaberCommand.SetMaximumPosition, 0)]
    [InlineData(ZaberCommand.SetMaximumPosition, 16_777_216)]
    [InlineData(ZaberCommand.SetCurrentPosition, -1)]
    [InlineData(ZaberCommand.SetDeviceMode, 1 << 10)]
    [InlineData(ZaberCommand.SetDeviceMode, 1 << 16)]
    public async Task SetSetting_InvalidValue_ErrorIsTheCommandNumber(ZaberCommand command, int value)
    {
        await using var bench = MachineBench.Create();

        var reply = await bench.RequestAsync(1, command, value);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.Error, (int)command), reply);
    }

    [Fact(Timeout = 20_000)]
    public async Task SetCurrentPosition_AboveMaximum_Error45()
    {
        await using var bench = MachineBench.Create();

        var reply = await bench.RequestAsync(1, ZaberCommand.SetCurrentPosition, (int)MaxPosition + 1);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.Error, 45), reply);
    }

    [Theory(Timeout = 20_000)]
    [InlineData(ZaberCommand.SetTargetSpeed, 4300)]
    [InlineData(ZaberCommand.SetHomeSpeed, 1)]
    [InlineData(ZaberCommand.SetAcceleration, 0)]
    [InlineData(ZaberCommand.SetMaximumPosition, 300_000)]
    [InlineData(ZaberCommand.SetDeviceMode, 0b1000_1000)]
    public async Task SetSetting_Valid_EchoesAndReturnSettingReadsItBack(ZaberCommand command, int value)
    {
        await using var bench = MachineBench.Create();

        var reply = await bench.RequestAsync(2, command, value);
        var read = await bench.RequestAsync(2, ZaberCommand.ReturnSetting, (int)command);

        Assert.Equal(new ZaberFrame(2, command, value), reply);
        Assert.Equal(new ZaberFrame(2, command, value), read);
    }

    [Fact(Timeout = 20_000)]
    public async Task SetCurrentPosition_Valid_SetsPositionAndHomedBit()
    {
        await using var bench = MachineBench.Create();

        var reply = await bench.RequestAsync(1, ZaberCommand.SetCurrentPosition, 1234);
        var position = await bench.RequestAsync(1, ZaberCommand.ReturnCurrentPosition, 0);
        var mode = await bench.RequestAsync(1, ZaberCommand.ReturnSetting, (int)ZaberCommand.SetDeviceMode);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.SetCurrentPosition, 1234), reply);
        Assert.Equal(1234, position.Data);
        Assert.Equal(0x80, mode.Data & 0x80);
    }

    [Fact(Timeout = 20_000)]
    public async Task ReturnSetting_UnknownSetting_Error53()
    {
        await using var bench = MachineBench.Create();

        var reply = await bench.RequestAsync(1, ZaberCommand.ReturnSetting, 99);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.Error, 53), reply);
    }

    [Fact(Timeout = 20_000)]
    public async Task ReturnSetting_TargetSpeed_ReplyCommandIsTheSettingNumber()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { TargetSpeedData = 1234 });

        var reply = await bench.RequestAsync(1, ZaberCommand.ReturnSetting, 42);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.SetTargetSpeed, 1234), reply);
    }

    [Fact(Timeout = 20_000)]
    public async Task ReturnStatus_MovingThenIdle_ReportsTheMoveCommandThenZero()
    {
        await using var bench = MachineBench.Create();
        await bench.SendAsync(1, ZaberCommand.MoveAbsolute, 0);
        await bench.WaitAsync(TimeSpan.FromSeconds(1));

        var moving = await bench.RequestAsync(1, ZaberCommand.ReturnStatus, 0);
        var moveReply = (await bench.ReceiveAsync()).Frame;
        var idle = await bench.RequestAsync(1, ZaberCommand.ReturnStatus, 0);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.ReturnStatus, 20), moving);
        Assert.Equal(ZaberCommand.MoveAbsolute, moveReply.Command);
        Assert.Equal(new ZaberFrame(1, ZaberCommand.ReturnStatus, 0), idle);
    }

    [Fact(Timeout = 20_000)]
    public async Task DeviceModeBit0_AutoReplyDisabled_MovesAreSilentButReturnsAnswer()
    {
        await using var bench = MachineBench.Create();
        await bench.SendAsync(1, ZaberCommand.SetDeviceMode, 1);

        await bench.SendAsync(1, ZaberCommand.MoveAbsolute, 1000);
        Assert.Null(await bench.TryReceiveAsync(TimeSpan.FromMinutes(5)));
        var position = await bench.RequestAsync(1, ZaberCommand.ReturnCurrentPosition, 0);
        var echo = await bench.RequestAsync(1, ZaberCommand.EchoData, 5);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 1000), position);
        Assert.Equal(new ZaberFrame(1, ZaberCommand.EchoData, 5), echo);
    }

    [Fact(Timeout = 20_000)]
    public async Task DeviceModeBit0_AutoReplyDisabled_ReturnSettingStillAnswers()
    {
        await using var bench = MachineBench.Create();
        await bench.SendAsync(1, ZaberCommand.SetDeviceMode, 1);

        var mode = await bench.RequestAsync(1, ZaberCommand.ReturnSetting, (int)ZaberCommand.SetDeviceMode);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.SetDeviceMode, 1), mode);
    }

    [Fact(Timeout = 20_000)]
    public async Task DeviceModeBit4_MoveTracking_Reply8EveryQuarterSecondThenTheMoveReply()
    {
        await using var bench = MachineBench.Create();
        await bench.RequestAsync(1, ZaberCommand.SetDeviceMode, 16);
        var sent = bench.Now;

        await bench.SendAsync(1, ZaberCommand.MoveRelative, -20_000);
        var frames = new List<(ZaberFrame Frame, TimeSpan At)>();
        do
        {
            frames.Add(await bench.ReceiveAsync());
        }
        while (frames[^1].Frame.Command == ZaberCommand.MoveTracking);

        var tracking = frames[..^1];
        Assert.NotEmpty(tracking);
        Assert.Equal(new ZaberFrame(1, ZaberCommand.MoveRelative, (int)MaxPosition - 20_000), frames[^1].Frame);
        for (var i = 0; i < tracking.Count; i++)
        {
            // The first tick is a quarter second after the move started (the command's last byte arrived), plus the reply's frame time.
            AssertTicks(MachineBench.FrameTime + TimeSpan.FromMilliseconds(250 * (i + 1)) + MachineBench.FrameTime, tracking[i].At - sent);
        }

        Assert.True(tracking.Select(t => t.Frame.Data).Zip(tracking.Skip(1).Select(t => t.Frame.Data)).All(p => p.First > p.Second), "positions must fall");
    }

    [Fact(Timeout = 20_000)]
    public async Task Renumber_OneDevice_RepliesFromTheNewNumberAfterHalfASecond()
    {
        await using var bench = MachineBench.Create();
        var sent = bench.Now;

        await bench.SendAsync(2, ZaberCommand.Renumber, 5);
        var (reply, at) = await bench.ReceiveAsync();
        var echo = await bench.RequestAsync(5, ZaberCommand.EchoData, 1);

        Assert.Equal(new ZaberFrame(5, ZaberCommand.Renumber, 4212), reply);
        AssertTicks(MachineBench.FrameTime + TimeSpan.FromMilliseconds(500) + MachineBench.FrameTime, at - sent);
        Assert.Equal(5, echo.Device);
        Assert.Null(await bench.TryReceiveAsync(TimeSpan.FromSeconds(1)));
        await bench.SendAsync(2, ZaberCommand.EchoData, 1);
        Assert.Null(await bench.TryReceiveAsync(TimeSpan.FromSeconds(1)));
    }

    [Fact(Timeout = 20_000)]
    public async Task Renumber_Broadcast_NumbersTheChainFromOne()
    {
        var profile = MachineProfile.Default with
        {
            X = MachineProfile.Default.X with { DeviceNumber = 7 },
            Y = MachineProfile.Default.Y with { DeviceNumber = 9 },
        };
        await using var bench = MachineBench.Create(profile: profile);

        await bench.SendAsync(0, ZaberCommand.Renumber, 0);
        var first = (await bench.ReceiveAsync()).Frame;
        var second = (await bench.ReceiveAsync()).Frame;

        Assert.Equal((1, 2), (first.Device, second.Device));
    }

    [Fact(Timeout = 20_000)]
    public async Task Renumber_OutOfRange_Error2()
    {
        await using var bench = MachineBench.Create();

        var reply = await bench.RequestAsync(1, ZaberCommand.Renumber, 255);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.Error, 2), reply);
    }

    [Fact(Timeout = 20_000)]
    public async Task Reset_NoReplyAndBackToPowerUpState()
    {
        await using var bench = MachineBench.Create();
        await bench.RequestAsync(1, ZaberCommand.SetTargetSpeed, 3000);
        await bench.RequestAsync(1, ZaberCommand.Home, 0);

        await bench.SendAsync(1, ZaberCommand.Reset, 0);
        Assert.Null(await bench.TryReceiveAsync(TimeSpan.FromSeconds(1)));
        var position = await bench.RequestAsync(1, ZaberCommand.ReturnCurrentPosition, 0);
        var mode = await bench.RequestAsync(1, ZaberCommand.ReturnSetting, (int)ZaberCommand.SetDeviceMode);
        var speed = await bench.RequestAsync(1, ZaberCommand.ReturnSetting, (int)ZaberCommand.SetTargetSpeed);

        Assert.Equal(MaxPosition, position.Data);
        Assert.Equal(0, mode.Data & 0x80);
        Assert.Equal(3000, speed.Data);
    }

    [Fact(Timeout = 20_000)]
    public async Task Reset_DuringMove_TheMoveNeverReplies()
    {
        await using var bench = MachineBench.Create();
        await bench.SendAsync(1, ZaberCommand.MoveAbsolute, 0);
        await bench.WaitAsync(TimeSpan.FromSeconds(1));

        await bench.SendAsync(1, ZaberCommand.Reset, 0);

        Assert.Null(await bench.TryReceiveAsync(TimeSpan.FromMinutes(2)));
    }

    private static void AssertTicks(TimeSpan expected, TimeSpan actual) =>
        Assert.True(Math.Abs((expected - actual).Ticks) <= 2, $"expected {expected} (virtual), got {actual}");
}
