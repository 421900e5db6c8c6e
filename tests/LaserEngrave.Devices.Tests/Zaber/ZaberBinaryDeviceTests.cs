using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Motion;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Tests.Fakes;
using LaserEngrave.Devices.Zaber;
using LaserEngrave.Wire.Zaber;
using Microsoft.Extensions.Time.Testing;

namespace LaserEngrave.Devices.Tests.Zaber;

/// <summary>A Zaber axis against fake devices in memory. Request-and-reply tests stand on a <c>FakeTimeProvider</c> (time
/// never moves); the move timeout and the unsolicited reply run on the simulation's loop.</summary>
public class ZaberBinaryDeviceTests
{
    private static readonly CancellationToken None = CancellationToken.None;

    [Fact]
    public async Task MoveAbsoluteAsync_FirstMove_ReadsSpeedAccelerationAndMaximumThenMoves()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());

        var final = await rig.X.MoveAbsoluteAsync(12345, None).Within();

        Assert.Equal(12345, final);
        Assert.Equal(12345, rig.Wire[1].Position);
        Assert.Equal(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 12345), rig.Wire.Log[^1]);
        var settingsRead = rig.Wire.Log.Where(f => f.Command == ZaberCommand.ReturnSetting).Select(f => (ZaberCommand)f.Data).ToList();
        Assert.Contains(ZaberCommand.SetTargetSpeed, settingsRead);
        Assert.Contains(ZaberCommand.SetAcceleration, settingsRead);
        Assert.Equal(rig.Wire[1].SpeedData, rig.X.SpeedData);
        Assert.Equal(rig.Wire[1].AccelerationData, rig.X.AccelerationData);
        Assert.Equal(12345, rig.X.LastKnownPosition);
    }

    [Fact]
    public async Task MoveAbsoluteAsync_SecondMove_DoesNotReadSettingsAgain()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());
        await rig.X.MoveAbsoluteAsync(100, None).Within();
        var before = rig.Wire.Log.Count;

        await rig.X.MoveAbsoluteAsync(200, None).Within();

        Assert.Equal([new ZaberFrame(1, ZaberCommand.MoveAbsolute, 200)], rig.Wire.Log.Skip(before));
    }

    [Fact]
    public async Task MoveAbsoluteAsync_DeviceSilent_TimeoutFollowsDistanceSpeedAndAcceleration()
    {
        await using var rig = new ZaberRig();

        await rig.RunAsync(async () =>
        {
            await rig.X.SetTargetSpeedAsync(1000, None);
            await rig.X.SetAccelerationAsync(20, None);
            await rig.X.MoveAbsoluteAsync(0, None);
            rig.Wire.Intercept = f => f.Command == ZaberCommand.MoveAbsolute ? FakeZaberChain.Hold : null;

            const long distance = 300000;
            var move = rig.X.MoveAbsoluteAsync(distance, None);
            await rig.Wire.NextAsync(ZaberCommand.MoveAbsolute);
            var sentAt = rig.Time.Elapsed;
            var travelSeconds = new TrapezoidProfile(
                distance, StageUnits.SpeedMicrostepsPerS(1000), StageUnits.AccelerationMicrostepsPerS2(20)).Duration;
            var travel = TimeSpan.FromSeconds(travelSeconds);

            // A slow move must not be given up while the stage can still be travelling ...
            await Task.Delay(travel, rig.Time);
            await rig.Time.AssertStillPendingAsync(move);

            // ... but a silent device is a fault before long: the travel time x 1.5 + 1 s after the move was sent.
            var error = await VirtualTime.ThrowsAsync<DeviceTimeoutException>(move);
            var options = rig.Connection.Options;
            Assert.Equal(TimeSpan.FromSeconds(travelSeconds * options.MoveTimeoutFactor) + options.MoveTimeoutMargin, rig.Time.Elapsed - sentAt);
            Assert.True(rig.Time.Elapsed - sentAt <= travel + travel + TimeSpan.FromSeconds(2));
            Assert.Contains("device 1 (X) did not reply to Move Absolute 300000", error.Message, StringComparison.Ordinal);
            Assert.Null(rig.X.LastKnownPosition);
        });
    }

    [Fact]
    public async Task MoveTimeout_LongerMoveOrSlowerSpeed_AllowsMoreTime()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());

        var shortMove = rig.X.MoveTimeout(1000, 2000, 100);
        var longMove = rig.X.MoveTimeout(500000, 2000, 100);
        var slowMove = rig.X.MoveTimeout(500000, 200, 100);

        Assert.True(longMove > shortMove);
        Assert.True(slowMove > longMove);
        Assert.True(slowMove.TotalSeconds > 500000 / StageUnits.SpeedMicrostepsPerS(200));
    }

    [Fact]
    public async Task MoveRelativeAsync_Negative_SendsSignedDataAndReturnsFinalPosition()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());
        rig.Wire[2].Position = 5000;

        var final = await rig.Y.MoveRelativeAsync(-1500, None).Within();

        Assert.Equal(3500, final);
        Assert.Equal(new ZaberFrame(2, ZaberCommand.MoveRelative, -1500), rig.Wire.Log[^1]);
    }

    [Fact]
    public async Task HomeAsync_Homes_ReturnsZeroAndMarksHomed()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());
        await rig.X.IdentifyAsync(None).Within();
        Assert.Equal(0, rig.X.DeviceMode & ZaberBinaryDevice.HomeStatusBit);

        var final = await rig.X.HomeAsync(None).Within();

        Assert.Equal(0, final);
        Assert.NotEqual(0, rig.X.DeviceMode!.Value & ZaberBinaryDevice.HomeStatusBit);
        Assert.Equal(new ZaberFrame(1, ZaberCommand.Home, 0), rig.Wire.Log[^1]);
    }

    [Fact]
    public async Task MoveAtConstantSpeedAsync_RepliesAtOnce_ThenStopReturnsWhereItStopped()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());

        Assert.Equal(-300, await rig.X.MoveAtConstantSpeedAsync(-300, None).Within());
        Assert.Null(rig.X.LastKnownPosition);
        rig.Wire[1].Position = 777;
        Assert.Equal(777, await rig.X.StopAsync(None).Within());
        Assert.Equal(777, rig.X.LastKnownPosition);
    }

    [Fact]
    public async Task SetDeviceModeAsync_SetAndClearBits_KeepsTheOtherBits()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());
        rig.Wire[1].Mode = 0x80 | 0x08 | 0x4000;

        var mode = await rig.X.SetDeviceModeAsync(0x10, 0x08, None).Within();

        Assert.Equal(0x80 | 0x10 | 0x4000, mode);
        Assert.Equal(0x80 | 0x10 | 0x4000, rig.Wire[1].Mode);
        Assert.Contains(new ZaberFrame(1, ZaberCommand.ReturnSetting, (int)ZaberCommand.SetDeviceMode), rig.Wire.Log);
        Assert.Contains(new ZaberFrame(1, ZaberCommand.SetDeviceMode, 0x80 | 0x10 | 0x4000), rig.Wire.Log);
    }

    [Fact]
    public async Task SetDeviceModeAsync_NothingToChange_SendsNoSetDeviceMode()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());
        rig.Wire[1].Mode = 0x10;

        await rig.X.SetDeviceModeAsync(0x10, 0, None).Within();

        Assert.DoesNotContain(rig.Wire.Log, f => f.Command == ZaberCommand.SetDeviceMode);
    }

    [Fact]
    public async Task SettersAndReturns_RoundTripThroughTheDevice()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());

        await rig.Y.SetTargetSpeedAsync(4300, None).Within();
        await rig.Y.SetAccelerationAsync(45, None).Within();
        Assert.Equal(500000, await rig.Y.SetMaximumPositionAsync(500000, None).Within());
        Assert.Equal(1234, await rig.Y.SetCurrentPositionAsync(1234, None).Within());

        Assert.Equal(4300, await rig.Y.ReturnSettingAsync(ZaberCommand.SetTargetSpeed, None).Within());
        Assert.Equal(45, await rig.Y.ReturnSettingAsync(ZaberCommand.SetAcceleration, None).Within());
        Assert.Equal(500000, await rig.Y.ReturnSettingAsync(ZaberCommand.SetMaximumPosition, None).Within());
        Assert.Equal(1234, await rig.Y.GetPositionAsync(None).Within());
        Assert.Equal(4300, rig.Y.SpeedData);
        Assert.Equal(45, rig.Y.AccelerationData);
    }

    [Fact]
    public async Task ReturnSettingAsync_InvalidSetting_ThrowsWithSettingInvalidMeaning()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());

        var error = await Assert.ThrowsAsync<ZaberException>(() => rig.X.ReturnSettingAsync((ZaberCommand)99, None).Within());

        Assert.Equal(ZaberErrorCodes.SettingInvalid, error.ErrorCode);
        Assert.Equal(ZaberCommand.ReturnSetting, error.Command);
        Assert.Contains("Return Setting 99", error.Message, StringComparison.Ordinal);
        Assert.Contains(ZaberErrorCodes.Describe(53), error.Message, StringComparison.Ordinal);
    }

    [Fact]
    public async Task IdentifyAsync_ReadsIdFirmwareModeAndMaximum()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());
        rig.Wire[2].DeviceId = 4711;
        rig.Wire[2].Firmware = 522;
        rig.Wire[2].Mode = 0x88;
        rig.Wire[2].Settings[(byte)ZaberCommand.SetMaximumPosition] = 282204;

        var identity = await rig.Y.IdentifyAsync(None).Within();

        Assert.Equal(new AxisIdentity(2, 4711, 522, 0x88, 282204), identity);
        Assert.True(identity.IsHomed);
        Assert.Equal("5.22", identity.FirmwareText);
    }

    [Fact]
    public async Task EchoAsync_ReturnsTheSameData()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());

        Assert.Equal(-123456, await rig.X.EchoAsync(-123456, None).Within());
    }

    [Fact]
    public async Task ReturnDeviceIdAndFirmware_ReturnTheDeviceValues()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());
        rig.Wire[1].DeviceId = 5001;
        rig.Wire[1].Firmware = 504;

        Assert.Equal(5001, await rig.X.ReturnDeviceIdAsync(None).Within());
        Assert.Equal(504, await rig.X.ReturnFirmwareVersionAsync(None).Within());
    }

    [Fact]
    public async Task RenumberAsync_ReplyComesFromTheNewNumber_DeviceTakesIt()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());

        await rig.Y.RenumberAsync(7, None).Within();

        Assert.Equal(7, rig.Y.DeviceNumber);
        Assert.Equal(7, rig.Wire.Devices[1].Number);
        Assert.Equal("device 7 (Y)", rig.Y.Description);
        rig.Wire.Devices[1].Position = 99;
        Assert.Equal(99, await rig.Y.GetPositionAsync(None).Within());
    }

    [Fact]
    public async Task ResetAsync_SendsResetAndForgetsThePosition()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());
        await rig.X.GetPositionAsync(None).Within();

        await rig.X.ResetAsync(None).Within();

        Assert.Equal(new ZaberFrame(1, ZaberCommand.Reset, 0), await rig.Wire.NextAsync(ZaberCommand.Reset));
        Assert.Null(rig.X.LastKnownPosition);
    }

    [Fact]
    public async Task UnsolicitedReply_LimitActive_ReachesOnlyItsDevice()
    {
        await using var rig = new ZaberRig();
        var xEvents = new List<ZaberFrame>();
        var yEvents = new List<ZaberFrame>();
        rig.X.UnsolicitedReply += (_, e) => xEvents.Add(e.Reply);
        rig.Y.UnsolicitedReply += (_, e) => yEvents.Add(e.Reply);

        await rig.RunAsync(async () =>
        {
            await rig.Wire.SendAsync(new ZaberFrame(1, ZaberCommand.LimitActive, 604724));
            await rig.Time.SettleAsync();

            Assert.Single(xEvents);
            Assert.Empty(yEvents);
            Assert.Equal(604724, rig.X.LastKnownPosition);
        });
    }

    [Fact]
    public async Task MoveAbsoluteAsync_BothAxesAtOnce_EachCompletesWithItsTarget()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());
        await rig.X.IdentifyAsync(None).Within();
        await rig.Y.IdentifyAsync(None).Within();

        var moves = await Task.WhenAll(rig.X.MoveAbsoluteAsync(1111, None), rig.Y.MoveAbsoluteAsync(2222, None)).Within();

        Assert.Equal([1111L, 2222L], moves);
    }
}
