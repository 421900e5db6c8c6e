using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Tests.Fakes;
using LaserEngrave.Devices.Zaber;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Wire.Zaber;
using Microsoft.Extensions.Time.Testing;

namespace LaserEngrave.Devices.Tests.Zaber;

/// <summary>The Zaber connection against fake devices in memory. Tests in which time never moves and nothing needs to be
/// looked at between the reader's steps stand on a <c>FakeTimeProvider</c>; the others run on the simulation's loop,
/// where time moves only when nothing else is left to do, so timeouts are asserted at their exact virtual times.</summary>
public class ZaberConnectionTests
{
    private static readonly CancellationToken None = CancellationToken.None;

    [Fact]
    public async Task RequestAsync_DeviceReplies_ReturnsItsReply()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());
        rig.Wire[1].Position = 4242;

        var reply = await rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 0), None).Within();

        Assert.Equal(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 4242), reply);
    }

    [Fact(Timeout = 20_000)]
    public async Task RecentRoundTripsMs_EveryReadLate_CountsToTheReplysArrivalNotToTheLateReader()
    {
        // Issue 34: preflight sizes every guard from these round trips; a host late to read one reply (the twin: 5-60 ms)
        // made it look like adapter spread and widened every line's guards up to 6x for the whole run.
        var late = new HostLateness(0, 0, 0) { LateReadProbability = 1, LateReadMs = 60 };
        var options = new LaserEngrave.Simulator.SimulatorOptions { HostLateness = late, AdapterLatency = new Jitter(1, 0) };
        await using var machine = LaserEngrave.Simulator.SimulatedMachine.CreateInProcess(LaserEngrave.Core.Geometry.MachineProfile.Default, options);
        var time = machine.TimeProvider;
        await using var connection = new ZaberConnection(machine.StageLink, time);

        var answeredMs = await machine.RunAsync(async () =>
        {
            var start = time.GetTimestamp();
            await connection.RequestAsync(new ZaberFrame(1, ZaberCommand.EchoData, 7), None);
            return time.GetElapsedTime(start).TotalMilliseconds;
        });

        // 6 bytes at 9600 baud each way (6.25 ms) and the adapter's 1 ms each way; the waiter itself ran 5-60 ms later.
        var roundTrip = Assert.Single(connection.RecentRoundTripsMs);
        Assert.Equal(14.5, roundTrip, 1);
        Assert.InRange(answeredMs, 14.5 + HostLateness.ShortestStallMs, 14.5 + 61);
    }

    [Fact]
    public async Task RequestAsync_RepliesOfBothAxesInterleaved_EachReachesItsOwnWaiter()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());
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

        await rig.RunAsync(async () =>
        {
            var x = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 0), None);
            var y = rig.Connection.RequestAsync(new ZaberFrame(2, ZaberCommand.ReturnCurrentPosition, 0), None);
            await rig.Wire.NextAsync();
            await rig.Wire.NextAsync();

            await rig.Wire.SendAsync(new ZaberFrame(2, ZaberCommand.ReturnCurrentPosition, 22));

            Assert.Equal(22, (await y).Data);
            await rig.Time.AssertStillPendingAsync(x);
            await rig.Wire.SendAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 11));
            Assert.Equal(11, (await x).Data);
            Assert.Equal(TimeSpan.Zero, rig.Time.Elapsed);
        });
    }

    [Fact]
    public async Task RequestAsync_ReplyArrivesOneByteAtATime_IsAssembled()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());
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
        await using var rig = new ZaberRig(new FakeTimeProvider());
        rig.Wire[2].Settings[(byte)ZaberCommand.SetTargetSpeed] = 4300;

        var reply = await rig.Connection.RequestAsync(new ZaberFrame(2, ZaberCommand.ReturnSetting, (int)ZaberCommand.SetTargetSpeed), None).Within();

        Assert.Equal(new ZaberFrame(2, ZaberCommand.SetTargetSpeed, 4300), reply);
    }

    [Fact]
    public async Task RequestAsync_ErrorReply_ThrowsZaberExceptionNamingPortDeviceCommandAndMeaning()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());

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

        await rig.RunAsync(async () =>
        {
            var move = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 500), TimeSpan.FromSeconds(5), None);
            await rig.Wire.NextAsync();

            var speed = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.SetTargetSpeed, 99999), None);

            var error = await VirtualTime.ThrowsAsync<ZaberException>(speed);
            Assert.Equal(ZaberCommand.SetTargetSpeed, error.Command);
            await rig.Time.AssertStillPendingAsync(move);
            await rig.Wire.SendAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 500));
            Assert.Equal(500, (await move).Data);
            Assert.Equal(TimeSpan.Zero, rig.Time.Elapsed);
        });
    }

    [Fact]
    public async Task RequestAsync_ErrorWithCodeOfNoPendingCommand_GoesToTheOldestRequestOfThatDevice()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;

        await rig.RunAsync(async () =>
        {
            var home = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.Home, 0), TimeSpan.FromSeconds(5), None);
            await rig.Wire.NextAsync();
            var other = rig.Connection.RequestAsync(new ZaberFrame(2, ZaberCommand.Home, 0), TimeSpan.FromSeconds(5), None);
            await rig.Wire.NextAsync();

            await rig.Wire.SendAsync(new ZaberFrame(1, ZaberCommand.Error, 14));

            var error = await VirtualTime.ThrowsAsync<ZaberException>(home);
            Assert.Equal(14, error.ErrorCode);
            Assert.Contains("voltage low", error.Message, StringComparison.Ordinal);
            await rig.Time.AssertStillPendingAsync(other);
            Assert.Equal(TimeSpan.Zero, rig.Time.Elapsed);

            // The other request ends with its own timeout, 5 s after it was sent.
            await VirtualTime.ThrowsAsync<DeviceTimeoutException>(other);
            Assert.Equal(TimeSpan.FromSeconds(5), rig.Time.Elapsed);
        });
    }

    [Fact]
    public async Task UnsolicitedReply_MoveTrackingDuringAMove_RaisesEventAndLeavesTheMovePending()
    {
        await using var rig = new ZaberRig();
        var events = new List<ZaberFrame>();
        rig.Connection.UnsolicitedReply += (_, e) => events.Add(e.Reply);
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;

        await rig.RunAsync(async () =>
        {
            var move = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 9000), TimeSpan.FromSeconds(5), None);
            await rig.Wire.NextAsync();

            await rig.Wire.SendAsync(
                new ZaberFrame(1, ZaberCommand.MoveTracking, 3000),
                new ZaberFrame(2, ZaberCommand.ManualMoveTracking, 77),
                new ZaberFrame(1, ZaberCommand.LimitActive, 0));
            await rig.Time.SettleAsync();

            Assert.Equal(3, events.Count);
            Assert.Equal(new ZaberFrame(1, ZaberCommand.MoveTracking, 3000), events[0]);
            Assert.Equal(new ZaberFrame(2, ZaberCommand.ManualMoveTracking, 77), events[1]);
            Assert.Equal(ZaberCommand.LimitActive, events[2].Command);
            Assert.False(move.IsCompleted);
        });
    }

    [Fact]
    public async Task OnBytes_PartialFrameThenGapLongerThan10Ms_DropsThePartialBytes()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;

        await rig.RunAsync(async () =>
        {
            var request = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 0), None);
            await rig.Wire.NextAsync();

            await rig.Wire.SendRawAsync([1, 60, 9]);
            await Task.Delay(TimeSpan.FromMilliseconds(11), rig.Time);
            Assert.Equal(3, rig.Connection.BytesReceived);
            Assert.False(rig.Saw(ZaberLineEvent.PartialFrameDropped));
            await rig.Wire.SendAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 123));

            Assert.Equal(123, (await request).Data);
            await rig.Time.SettleAsync();
            Assert.True(rig.Saw(ZaberLineEvent.PartialFrameDropped));
        });
    }

    [Fact]
    public async Task OnBytes_FrameSplitByAGapShorterThan10Ms_IsKept()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;

        await rig.RunAsync(async () =>
        {
            var request = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 0), None);
            await rig.Wire.NextAsync();
            var bytes = new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 321).ToBytes();

            await rig.Wire.SendRawAsync(bytes[..3]);
            await Task.Delay(TimeSpan.FromMilliseconds(9), rig.Time);
            Assert.Equal(3, rig.Connection.BytesReceived);
            await rig.Wire.SendRawAsync(bytes[3..]);

            Assert.Equal(321, (await request).Data);
            await rig.Time.SettleAsync();
            Assert.False(rig.Saw(ZaberLineEvent.PartialFrameDropped));
        });
    }

    [Theory]
    [InlineData(4, false)]
    [InlineData(12, true)]
    public async Task OnBytes_FrameInTwoPiecesReadLate_JudgedOnTheGapBetweenTheirArrivals(int gapMs, bool dropped)
    {
        // Piece one is read as it arrives; piece two arrives gapMs later but the host only reads it at 15 ms (a busy
        // machine). Stamped when read, a 4 ms gap would look like 15 ms and the frame would be dropped.
        using var clock = new VirtualTimeProvider();
        var (host, device) = InMemorySerialLink.CreatePair(ZaberRig.Port, clock);
        var connection = new ZaberConnection(host, clock);
        var events = new List<ZaberLineEvent>();
        connection.LineEvent += (_, e) => events.Add(e.Kind);

        await clock.RunTestAsync(async () =>
        {
            var request = connection.RequestAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 0), None);
            var bytes = new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 321).ToBytes();
            var start = clock.GetTimestamp();

            await device.WriteArrivedAsync(bytes[..3], start);
            await Task.Delay(TimeSpan.FromMilliseconds(15), clock);
            Assert.Equal(3, connection.BytesReceived);
            await device.WriteArrivedAsync(bytes[3..], start + TimeSpan.FromMilliseconds(gapMs).Ticks);
            await clock.SettleAsync();

            Assert.Equal(6, connection.BytesReceived);
            Assert.Equal(dropped, events.Contains(ZaberLineEvent.PartialFrameDropped));
            Assert.Equal(!dropped, request.IsCompletedSuccessfully);
            if (dropped)
            {
                // Piece two is now an unfinished frame of its own: the answer comes after it too has gone stale.
                await Task.Delay(TimeSpan.FromMilliseconds(11), clock);
                await device.WriteAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 654).ToBytes(), None);
            }

            Assert.Equal(dropped ? 654 : 321, (await request).Data);
            await connection.DisposeAsync();
            await device.DisposeAsync();
        });
    }

    [Theory]
    [InlineData(20, true)]
    [InlineData(600, false)]
    public async Task RequestAsync_ReplyArrivedInTimeButReadLate_AnswersUntilTwiceTheTimeout(int readLateMs, bool answered)
    {
        // The reply arrives at 100 ms; the host gets to it 500 + readLateMs ms in. Bytes already here when the time is up may
        // be the reply, so the wait looks again while they are read, for at most one more timeout.
        using var clock = new VirtualTimeProvider();
        var (host, device) = InMemorySerialLink.CreatePair(ZaberRig.Port, clock);
        var held = new HeldSerialLink(host);
        var connection = new ZaberConnection(held, clock);

        await clock.RunTestAsync(async () =>
        {
            var request = connection.RequestAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 0), None);
            await Task.Delay(TimeSpan.FromMilliseconds(100), clock);
            await device.WriteAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 321).ToBytes(), None);
            await Task.Delay(connection.Options.CommandTimeout - TimeSpan.FromMilliseconds(100) + TimeSpan.FromMilliseconds(readLateMs), clock);
            held.Release();

            if (answered)
            {
                Assert.Equal(321, (await request).Data);
            }
            else
            {
                var error = await VirtualTime.ThrowsAsync<DeviceTimeoutException>(request);
                Assert.Contains("within 500 ms", error.Message, StringComparison.Ordinal);
            }

            await connection.DisposeAsync();
            await device.DisposeAsync();
        });
    }

    [Fact]
    public async Task RequestAsync_NothingArrived_TimesOutAtTheTimeoutItself()
    {
        using var clock = new VirtualTimeProvider();
        var (host, device) = InMemorySerialLink.CreatePair(ZaberRig.Port, clock);
        var connection = new ZaberConnection(new HeldSerialLink(host), clock);

        await clock.RunTestAsync(async () =>
        {
            var start = clock.Elapsed;
            await VirtualTime.ThrowsAsync<DeviceTimeoutException>(connection.RequestAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 0), None));

            Assert.Equal(connection.Options.CommandTimeout, clock.Elapsed - start);
            await connection.DisposeAsync();
            await device.DisposeAsync();
        });
    }

    [Fact]
    public async Task OnBytes_GarbageByteBeforeAReply_DiscardsAndResynchronisesWithEcho()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = f => f.Command == ZaberCommand.ReturnCurrentPosition ? FakeZaberChain.Hold : null;

        await rig.RunAsync(async () =>
        {
            var request = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 0), None);
            await rig.Wire.NextAsync();

            await rig.Wire.SendRawAsync([0xEE, .. new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 5).ToBytes()]);
            await rig.Time.SettleAsync();
            Assert.True(rig.Saw(ZaberLineEvent.GarbageDropped));

            // The connection waits out the 10 ms gap on its clock, then checks the line with Echo Data.
            var echo = await rig.Wire.NextAsync(ZaberCommand.EchoData);
            Assert.Equal(TimeSpan.FromMilliseconds(10), rig.Time.Elapsed);
            Assert.Equal(1, echo.Device);
            await rig.Time.SettleAsync();
            Assert.True(rig.Saw(ZaberLineEvent.Resynchronised));

            // The garbled reply is gone: the request times out 500 ms after it was sent, and the next one works.
            await VirtualTime.ThrowsAsync<DeviceTimeoutException>(request);
            Assert.Equal(TimeSpan.FromMilliseconds(500), rig.Time.Elapsed);
            rig.Wire.Intercept = null;
            rig.Wire[1].Position = 6;
            Assert.Equal(6, await rig.X.GetPositionAsync(None));
        });
    }

    [Fact]
    public async Task RequestAsync_NoReply_TimesOutOnTheClockNamingPortDeviceAndCommand()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;

        await rig.RunAsync(async () =>
        {
            var request = rig.Connection.RequestAsync(new ZaberFrame(2, ZaberCommand.SetAcceleration, 50), None);
            await rig.Wire.NextAsync();

            var error = await VirtualTime.ThrowsAsync<DeviceTimeoutException>(request);

            Assert.Equal(rig.Connection.Options.CommandTimeout, rig.Time.Elapsed);
            Assert.Equal($"{ZaberRig.Port}: device 2 (Y) did not reply to Set Acceleration 50 within 500 ms", error.Message);
        });
    }

    [Fact]
    public async Task RequestAsync_AfterATimeout_ResynchronisesWithEcho()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = f => f.Command == ZaberCommand.ReturnDeviceId ? FakeZaberChain.Hold : null;

        await rig.RunAsync(async () =>
        {
            var request = rig.Connection.RequestAsync(new ZaberFrame(2, ZaberCommand.ReturnDeviceId, 0), None);
            await rig.Wire.NextAsync();
            await VirtualTime.ThrowsAsync<DeviceTimeoutException>(request);
            Assert.Equal(rig.Connection.Options.CommandTimeout, rig.Time.Elapsed);

            var echo = await rig.Wire.NextAsync(ZaberCommand.EchoData);

            Assert.Equal(rig.Connection.Options.CommandTimeout + rig.Connection.Options.PartialFrameTimeout, rig.Time.Elapsed);
            Assert.Equal(2, echo.Device);
            await rig.Time.SettleAsync();
            Assert.True(rig.Saw(ZaberLineEvent.Resynchronised));
        });
    }

    [Fact]
    public async Task RequestAsync_LinkDropsWhileWaiting_ThrowsLinkLostNamingPortDeviceAndCommand()
    {
        await using var rig = new ZaberRig(new FakeTimeProvider());
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

        await rig.RunAsync(async () =>
        {
            await rig.Wire.DisposeAsync();
            await rig.Time.SettleAsync();
            Assert.False(rig.Connection.IsOpen);

            var error = await VirtualTime.ThrowsAsync<LinkLostException>(rig.Y.HomeAsync(None));

            Assert.Contains("device 2 (Y)", error.Message, StringComparison.Ordinal);
            Assert.Equal(TimeSpan.Zero, rig.Time.Elapsed);
        });
    }

    [Fact]
    public async Task BroadcastAsync_TwoDevicesAnswer_CollectsBothUntilQuiet()
    {
        await using var rig = new ZaberRig();
        rig.Wire[1].DeviceId = 111;
        rig.Wire[2].DeviceId = 222;

        await rig.RunAsync(async () =>
        {
            var replies = await rig.Connection.BroadcastAsync(ZaberCommand.ReturnDeviceId, 0, TimeSpan.FromMilliseconds(500), None);

            // Both replies come at once; the broadcast then waits one quiet period for more.
            Assert.Equal(rig.Connection.Options.BroadcastQuietPeriod, rig.Time.Elapsed);
            Assert.Equal(12, rig.Connection.BytesReceived);
            Assert.Equal([new ZaberFrame(1, ZaberCommand.ReturnDeviceId, 111), new ZaberFrame(2, ZaberCommand.ReturnDeviceId, 222)], replies);
            Assert.Equal(new ZaberFrame(0, ZaberCommand.ReturnDeviceId, 0), rig.Wire.Log[0]);
        });
    }

    [Fact]
    public async Task BroadcastAsync_NobodyAnswers_ReturnsEmptyAfterTheFirstReplyTimeout()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;

        await rig.RunAsync(async () =>
        {
            var replies = await rig.Connection.BroadcastAsync(ZaberCommand.ReturnDeviceId, 0, TimeSpan.FromMilliseconds(300), None);

            Assert.Empty(replies);
            Assert.Equal(TimeSpan.FromMilliseconds(300), rig.Time.Elapsed);
        });
    }

    [Fact]
    public async Task RequestAsync_StopWhileMoving_InterruptsTheMoveAndAbsorbsItsLateReply()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;

        await rig.RunAsync(async () =>
        {
            var move = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 9000), TimeSpan.FromSeconds(5), None);
            await rig.Wire.NextAsync();

            var stop = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.Stop, 0), None);

            var interrupted = await VirtualTime.ThrowsAsync<ZaberInterruptedException>(move);
            Assert.Contains("interrupted by Stop", interrupted.Message, StringComparison.Ordinal);
            await rig.Wire.NextAsync();
            await rig.Wire.SendAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 4000), new ZaberFrame(1, ZaberCommand.Stop, 4000));
            Assert.Equal(4000, (await stop).Data);
            await rig.Time.SettleAsync();
            Assert.True(rig.Saw(ZaberLineEvent.UnmatchedReply));
            Assert.Equal(TimeSpan.Zero, rig.Time.Elapsed);
        });
    }

    [Fact]
    public async Task RequestAsync_NewMoveWhileMoving_LateReplyOfTheOldMoveDoesNotCompleteTheNewOne()
    {
        await using var rig = new ZaberRig();
        rig.Wire.Intercept = _ => FakeZaberChain.Hold;

        await rig.RunAsync(async () =>
        {
            var first = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 9000), TimeSpan.FromSeconds(5), None);
            await rig.Wire.NextAsync();
            var second = rig.Connection.RequestAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 100), TimeSpan.FromSeconds(5), None);
            await rig.Wire.NextAsync();
            await VirtualTime.ThrowsAsync<ZaberInterruptedException>(first);

            await rig.Wire.SendAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 3500));
            await rig.Time.AssertStillPendingAsync(second);
            await rig.Wire.SendAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 100));

            Assert.Equal(100, (await second).Data);
            Assert.Equal(TimeSpan.Zero, rig.Time.Elapsed);
        });
    }
}
