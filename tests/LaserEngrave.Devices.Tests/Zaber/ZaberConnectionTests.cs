using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Tests.Fakes;
using LaserEngrave.Devices.Zaber;

namespace LaserEngrave.Devices.Tests.Zaber;

public class ZaberConnectionTests
{
    private static readonly CancellationToken None = CancellationToken.None;

    [Fact]
    public async Task RequestAsync_DeviceReplies_ReturnsItsReply()
    {
        await using var rig = new ZaberRig();
        rig.Wire[1].Position = 4242;

        var reply = await rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 0), None).Within();

        Assert.Equal(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 4242), reply);
    }

    [Fact]
    public async Task RequestAsync_RepliesOfBothAxesInterleaved_EachReachesItsOwnWaiter()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;
        var x = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 1000), TimeSpan.FromSeconds(5), None);
        var y = rig.Connection.RequestAsync(new ZaberFrame(2, ZaberCommand.MoveAbsolute, 2000), TimeSpan.FromSeconds(5), None);
        await rig.Wire.NextAsync();
        await rig.Wire.NextAsync();

        // Y finishes first; both frames arrive back to back in one read.
        await rig.Wire.SendAsync(new ZaberFrame(2, ZaberCommand.MoveAbsolute, 2000), new ZaberFrame(1, ZaberCommand.MoveAbsolute, 1000));

        Assert.Equal(2000, (await y.Within()).Data);
        Assert.Equal(1000, (await x.Within()).Data);
    }

    [Fact]
    public async Task RequestAsync_SameCommandOnBothAxes_ReplyGoesToTheDeviceThatSentIt()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;
        var x = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 0), None);
        var y = rig.Connection.RequestAsync(new ZaberFrame(2, ZaberCommand.ReturnCurrentPosition, 0), None);
        await rig.Wire.NextAsync();
        await rig.Wire.NextAsync();

        await rig.Wire.SendAsync(new ZaberFrame(2, ZaberCommand.ReturnCurrentPosition, 22));

        Assert.Equal(22, (await y.Within()).Data);
        await Eventually.AssertStillPendingAsync(x);
        await rig.Wire.SendAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 11));
        Assert.Equal(11, (await x.Within()).Data);
    }

    [Fact]
    public async Task RequestAsync_ReplyArrivesOneByteAtATime_IsAssembled()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;
        var request = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 0), None);
        await rig.Wire.NextAsync();

        foreach (var b in new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, -5).ToBytes())
        {
            await rig.Wire.SendRawAsync([b]);
        }

        Assert.Equal(-5, (await request.Within()).Data);
    }

    [Fact]
    public async Task RequestAsync_ReturnSetting_MatchesTheReplyCarryingTheSettingNumber()
    {
        await using var rig = new ZaberRig();
        rig.Wire[2].Settings[(byte)ZaberCommand.SetTargetSpeed] = 4300;

        var reply = await rig.Connection.RequestAsync(new ZaberFrame(2, ZaberCommand.ReturnSetting, (int)ZaberCommand.SetTargetSpeed), None).Within();

        Assert.Equal(new ZaberFrame(2, ZaberCommand.SetTargetSpeed, 4300), reply);
    }

    [Fact]
    public async Task RequestAsync_ErrorReply_ThrowsZaberExceptionNamingPortDeviceCommandAndMeaning()
    {
        await using var rig = new ZaberRig();

        var error = await Assert.ThrowsAsync<ZaberException>(
            () => rig.X.MoveAbsoluteAsync(700000, None).Within());

        Assert.Equal(1, error.Device);
        Assert.Equal(ZaberCommand.MoveAbsolute, error.Command);
        Assert.Equal(ZaberErrorCodes.MoveAbsoluteInvalid, error.ErrorCode);
        Assert.Contains(ZaberRig.Port, error.Message, StringComparison.Ordinal);
        Assert.Contains("device 1 (X)", error.Message, StringComparison.Ordinal);
        Assert.Contains("Move Absolute 700000", error.Message, StringComparison.Ordinal);
        Assert.Contains(ZaberErrorCodes.Describe(20), error.Message, StringComparison.Ordinal);
    }

    [Fact]
    public async Task RequestAsync_ErrorWhileAMoveIsPending_GoesToTheRefusedCommandNotTheMove()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = f => f.Command == ZaberCommand.MoveAbsolute ? FakeZaberChain.Hold : null;
        var move = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 500), TimeSpan.FromSeconds(5), None);
        await rig.Wire.NextAsync();

        var speed = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.SetTargetSpeed, 99999), None);

        var error = await Assert.ThrowsAsync<ZaberException>(() => speed.Within());
        Assert.Equal(ZaberCommand.SetTargetSpeed, error.Command);
        await Eventually.AssertStillPendingAsync(move);
        await rig.Wire.SendAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 500));
        Assert.Equal(500, (await move.Within()).Data);
    }

    [Fact]
    public async Task RequestAsync_ErrorWithCodeOfNoPendingCommand_GoesToTheOldestRequestOfThatDevice()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;
        var home = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.Home, 0), TimeSpan.FromSeconds(5), None);
        await rig.Wire.NextAsync();
        var other = rig.Connection.RequestAsync(new ZaberFrame(2, ZaberCommand.Home, 0), TimeSpan.FromSeconds(5), None);
        await rig.Wire.NextAsync();

        await rig.Wire.SendAsync(new ZaberFrame(1, ZaberCommand.Error, 14));

        var error = await Assert.ThrowsAsync<ZaberException>(() => home.Within());
        Assert.Equal(14, error.ErrorCode);
        Assert.Contains("voltage low", error.Message, StringComparison.Ordinal);
        await Eventually.AssertStillPendingAsync(other);
    }

    [Fact]
    public async Task UnsolicitedReply_MoveTrackingDuringAMove_RaisesEventAndLeavesTheMovePending()
    {
        await using var rig = new ZaberRig();
        var events = new List<ZaberFrame>();
        rig.Connection.UnsolicitedReply += (_, e) =>
        {
            lock (events)
            {
                events.Add(e.Reply);
            }
        };
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;
        var move = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 9000), TimeSpan.FromSeconds(5), None);
        await rig.Wire.NextAsync();

        await rig.Wire.SendAsync(
            new ZaberFrame(1, ZaberCommand.MoveTracking, 3000),
            new ZaberFrame(2, ZaberCommand.ManualMoveTracking, 77),
            new ZaberFrame(1, ZaberCommand.LimitActive, 0));

        await Eventually.TrueAsync(() => { lock (events) { return events.Count == 3; } }, "three unsolicited replies");
        Assert.Equal(new ZaberFrame(1, ZaberCommand.MoveTracking, 3000), events[0]);
        Assert.Equal(new ZaberFrame(2, ZaberCommand.ManualMoveTracking, 77), events[1]);
        Assert.Equal(ZaberCommand.LimitActive, events[2].Command);
        Assert.False(move.IsCompleted);
    }

    [Fact]
    public async Task OnBytes_PartialFrameThenGapLongerThan10Ms_DropsThePartialBytes()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;
        var request = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 0), None);
        await rig.Wire.NextAsync();

        await rig.Wire.SendRawAsync([1, 60, 9]);
        await Eventually.TrueAsync(() => rig.Connection.BytesReceived == 3, "the host read the short frame");
        rig.Clock.Advance(TimeSpan.FromMilliseconds(11));
        await rig.Wire.SendAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 123));

        Assert.Equal(123, (await request.Within()).Data);
        // The reply's waiter may run before the reader thread raises the line event it noted for the same read.
        await Eventually.TrueAsync(() => rig.Saw(ZaberLineEvent.PartialFrameDropped), "the dropped partial frame reported");
    }

    [Fact]
    public async Task OnBytes_FrameSplitByAGapShorterThan10Ms_IsKept()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;
        var request = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 0), None);
        await rig.Wire.NextAsync();
        var bytes = new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 321).ToBytes();

        await rig.Wire.SendRawAsync(bytes[..3]);
        await Eventually.TrueAsync(() => rig.Connection.BytesReceived == 3, "the host read the first half");
        rig.Clock.Advance(TimeSpan.FromMilliseconds(9));
        await rig.Wire.SendRawAsync(bytes[3..]);

        Assert.Equal(321, (await request.Within()).Data);
        Assert.False(rig.Saw(ZaberLineEvent.PartialFrameDropped));
    }

    [Fact]
    public async Task OnBytes_GarbageByteBeforeAReply_DiscardsAndResynchronisesWithEcho()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = f => f.Command == ZaberCommand.ReturnCurrentPosition ? FakeZaberChain.Hold : null;
        var request = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 0), None);
        await rig.Wire.NextAsync();

        await rig.Wire.SendRawAsync([0xEE, .. new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 5).ToBytes()]);
        await Eventually.TrueAsync(() => rig.Saw(ZaberLineEvent.GarbageDropped), "garbage noticed");

        // The connection waits out the 10 ms gap on its clock, then checks the line with Echo Data.
        await rig.Clock.WaitForTimerAsync(TimeSpan.FromMilliseconds(10), TimeSpan.FromMilliseconds(10));
        rig.Clock.Advance(TimeSpan.FromMilliseconds(10));
        var echo = await rig.Wire.NextAsync(ZaberCommand.EchoData);
        Assert.Equal(1, echo.Device);
        await Eventually.TrueAsync(() => rig.Saw(ZaberLineEvent.Resynchronised), "resynchronised");

        // The garbled reply is gone: the request times out, and the next one works.
        await rig.Clock.WaitForTimerAsync(TimeSpan.FromMilliseconds(1), TimeSpan.FromMilliseconds(500));
        rig.Clock.Advance(TimeSpan.FromMilliseconds(500));
        await Assert.ThrowsAsync<DeviceTimeoutException>(() => request.Within());
        rig.Wire.Intercept = null;
        rig.Wire[1].Position = 6;
        Assert.Equal(6, await rig.X.GetPositionAsync(None).Within());
    }

    [Fact]
    public async Task RequestAsync_NoReply_TimesOutOnTheClockNamingPortDeviceAndCommand()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;
        var request = rig.Connection.RequestAsync(new ZaberFrame(2, ZaberCommand.SetAcceleration, 50), None);
        await rig.Wire.NextAsync();
        await rig.Clock.WaitForTimerAsync(rig.Connection.Options.CommandTimeout, rig.Connection.Options.CommandTimeout);

        rig.Clock.Advance(rig.Connection.Options.CommandTimeout - TimeSpan.FromMilliseconds(1));
        await Eventually.AssertStillPendingAsync(request);
        rig.Clock.Advance(TimeSpan.FromMilliseconds(1));

        var error = await Assert.ThrowsAsync<DeviceTimeoutException>(() => request.Within());
        Assert.Equal($"{ZaberRig.Port}: device 2 (Y) did not reply to Set Acceleration 50 within 500 ms", error.Message);
    }

    [Fact]
    public async Task RequestAsync_AfterATimeout_ResynchronisesWithEcho()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = f => f.Command == ZaberCommand.ReturnDeviceId ? FakeZaberChain.Hold : null;
        var request = rig.Connection.RequestAsync(new ZaberFrame(2, ZaberCommand.ReturnDeviceId, 0), None);
        await rig.Wire.NextAsync();
        await rig.Clock.WaitForTimerAsync();
        rig.Clock.Advance(rig.Connection.Options.CommandTimeout);
        await Assert.ThrowsAsync<DeviceTimeoutException>(() => request.Within());

        await rig.Clock.WaitForTimerAsync();
        rig.Clock.Advance(rig.Connection.Options.PartialFrameTimeout);

        var echo = await rig.Wire.NextAsync(ZaberCommand.EchoData);
        Assert.Equal(2, echo.Device);
        await Eventually.TrueAsync(() => rig.Saw(ZaberLineEvent.Resynchronised), "resynchronised");
    }

    [Fact]
    public async Task RequestAsync_LinkDropsWhileWaiting_ThrowsLinkLostNamingPortDeviceAndCommand()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;
        var move = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 10), TimeSpan.FromHours(1), None);
        await rig.Wire.NextAsync();

        await rig.Wire.DisposeAsync();

        var error = await Assert.ThrowsAsync<LinkLostException>(() => move.Within());
        Assert.Contains(ZaberRig.Port, error.Message, StringComparison.Ordinal);
        Assert.Contains("device 1 (X)", error.Message, StringComparison.Ordinal);
        Assert.Contains("Move Absolute 10", error.Message, StringComparison.Ordinal);
        Assert.False(rig.Connection.IsOpen);
    }

    [Fact]
    public async Task RequestAsync_AfterTheLinkDropped_FailsAtOnce()
    {
        await using var rig = new ZaberRig();
        await rig.Wire.DisposeAsync();
        await Eventually.TrueAsync(() => !rig.Connection.IsOpen, "the connection noticed");

        var error = await Assert.ThrowsAsync<LinkLostException>(() => rig.Y.HomeAsync(None).Within());

        Assert.Contains("device 2 (Y)", error.Message, StringComparison.Ordinal);
    }

    [Fact]
    public async Task BroadcastAsync_TwoDevicesAnswer_CollectsBothUntilQuiet()
    {
        await using var rig = new ZaberRig();
        rig.Wire[1].DeviceId = 111;
        rig.Wire[2].DeviceId = 222;

        var broadcast = rig.Connection.BroadcastAsync(ZaberCommand.ReturnDeviceId, 0, TimeSpan.FromMilliseconds(500), None);
        await Eventually.TrueAsync(() => rig.Connection.BytesReceived == 12, "both replies read");
        await rig.Clock.WaitForTimerAsync(rig.Connection.Options.BroadcastQuietPeriod, rig.Connection.Options.BroadcastQuietPeriod);
        rig.Clock.Advance(rig.Connection.Options.BroadcastQuietPeriod);

        var replies = await broadcast.Within();
        Assert.Equal([new ZaberFrame(1, ZaberCommand.ReturnDeviceId, 111), new ZaberFrame(2, ZaberCommand.ReturnDeviceId, 222)], replies);
        Assert.Equal(new ZaberFrame(0, ZaberCommand.ReturnDeviceId, 0), rig.Wire.Log[0]);
    }

    [Fact]
    public async Task BroadcastAsync_NobodyAnswers_ReturnsEmptyAfterTheFirstReplyTimeout()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;

        var broadcast = rig.Connection.BroadcastAsync(ZaberCommand.ReturnDeviceId, 0, TimeSpan.FromMilliseconds(300), None);
        await rig.Clock.WaitForTimerAsync(TimeSpan.FromMilliseconds(300), TimeSpan.FromMilliseconds(300));
        rig.Clock.Advance(TimeSpan.FromMilliseconds(300));

        Assert.Empty(await broadcast.Within());
    }

    [Fact]
    public async Task RequestAsync_StopWhileMoving_InterruptsTheMoveAndAbsorbsItsLateReply()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;
        var move = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 9000), TimeSpan.FromSeconds(5), None);
        await rig.Wire.NextAsync();

        var stop = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.Stop, 0), None);

        var interrupted = await Assert.ThrowsAsync<ZaberInterruptedException>(() => move.Within());
        Assert.Contains("interrupted by Stop", interrupted.Message, StringComparison.Ordinal);
        await rig.Wire.NextAsync();
        await rig.Wire.SendAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 4000), new ZaberFrame(1, ZaberCommand.Stop, 4000));
        Assert.Equal(4000, (await stop.Within()).Data);
        await Eventually.TrueAsync(() => rig.Saw(ZaberLineEvent.UnmatchedReply), "the late reply reported");
    }

    [Fact]
    public async Task RequestAsync_NewMoveWhileMoving_LateReplyOfTheOldMoveDoesNotCompleteTheNewOne()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;
        var first = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 9000), TimeSpan.FromSeconds(5), None);
        await rig.Wire.NextAsync();
        var second = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 100), TimeSpan.FromSeconds(5), None);
        await rig.Wire.NextAsync();
        await Assert.ThrowsAsync<ZaberInterruptedException>(() => first.Within());

        await rig.Wire.SendAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 3500));
        await Eventually.AssertStillPendingAsync(second);
        await rig.Wire.SendAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 100));

        Assert.Equal(100, (await second.Within()).Data);
    }
}
