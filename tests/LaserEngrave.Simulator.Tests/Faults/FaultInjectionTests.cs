using LaserEngrave.Simulator.Faults;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Simulator.Tests.Faults;

/// <summary>Each fault kind through the running machine, seen from the host's side of the wire.</summary>
public class FaultInjectionTests
{
    [Fact(Timeout = 20_000)]
    public async Task DropReply_AfterTwo_TheThirdReplyIsMissingAndTheRestArrive()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { FaultSpec = "drop-reply:stage:after=2" });

        for (var i = 1; i <= 4; i++)
        {
            await bench.SendAsync(1, ZaberCommand.EchoData, i);
        }

        Assert.Equal(1, (await bench.ReceiveAsync()).Frame.Data);
        Assert.Equal(2, (await bench.ReceiveAsync()).Frame.Data);
        Assert.Equal(4, (await bench.ReceiveAsync()).Frame.Data);
        Assert.Null(await bench.TryReceiveAsync(TimeSpan.FromSeconds(1)));
    }

    [Fact(Timeout = 20_000)]
    public async Task DropReply_OneCommandOnly_OnlyItsRepliesCountAndAreDropped()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { FaultSpec = "drop-reply:stage:command=60:after=1" });

        // Echoes are not counted; the first position query passes, the second is dropped, the third passes.
        await bench.SendAsync(1, ZaberCommand.EchoData, 1);
        await bench.SendAsync(1, ZaberCommand.ReturnCurrentPosition, 0);
        await bench.SendAsync(1, ZaberCommand.EchoData, 2);
        await bench.SendAsync(1, ZaberCommand.ReturnCurrentPosition, 0);
        await bench.SendAsync(1, ZaberCommand.ReturnCurrentPosition, 0);
        await bench.SendAsync(1, ZaberCommand.EchoData, 3);

        var commands = new List<ZaberCommand>();
        while (await bench.TryReceiveAsync(TimeSpan.FromSeconds(1)) is { } reply)
        {
            commands.Add(reply.Command);
        }

        Assert.Equal([ZaberCommand.EchoData, ZaberCommand.ReturnCurrentPosition, ZaberCommand.EchoData, ZaberCommand.ReturnCurrentPosition, ZaberCommand.EchoData], commands);
    }

    [Fact(Timeout = 20_000)]
    public async Task DropReply_OnAMove_TheMoveStillHappens()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { FaultSpec = "drop-reply:stage" });

        await bench.SendAsync(1, ZaberCommand.MoveAbsolute, 1000);
        Assert.Null(await bench.TryReceiveAsync(TimeSpan.FromMinutes(2)));
        var position = await bench.RequestAsync(1, ZaberCommand.ReturnCurrentPosition, 0);

        Assert.Equal(1000, position.Data);
    }

    [Fact(Timeout = 20_000)]
    public async Task Corrupt_CommandByte_ArrivesInverted()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { FaultSpec = "corrupt:stage:byte=1" });

        await bench.SendAsync(2, ZaberCommand.EchoData, 42);
        var raw = await bench.ReceiveRawAsync();

        Assert.Equal(new ZaberFrame(2, (ZaberCommand)(55 ^ 0xFF), 42).ToBytes(), raw);
    }

    [Fact(Timeout = 20_000)]
    public async Task Delay_Ms_TheReplyComesThatMuchLater()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { FaultSpec = "delay:stage:ms=500" });
        var sent = bench.Now;

        await bench.SendAsync(1, ZaberCommand.EchoData, 1);
        var (_, at) = await bench.ReceiveAsync();

        var expected = (2 * MachineBench.FrameTime) + TimeSpan.FromMilliseconds(500);
        Assert.True(Math.Abs((at - sent - expected).Ticks) <= 3, $"expected {expected}, got {at - sent}");
    }

    [Fact(Timeout = 20_000)]
    public async Task Error_OnAMove_RefusedWithTheCodeNothingMovesAndTheRecorderCountsIt()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { FaultSpec = "error:stage:code=20:after=1" });
        await bench.RequestAsync(1, ZaberCommand.EchoData, 0);

        var reply = await bench.RequestAsync(1, ZaberCommand.MoveAbsolute, 1000);
        var position = await bench.RequestAsync(1, ZaberCommand.ReturnCurrentPosition, 0);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.Error, 20), reply);
        Assert.Equal(bench.Machine.Profile.X.TravelMicrosteps, position.Data);
        var refused = Assert.Single(bench.Machine.Recorder.RefusedMoves);
        Assert.Equal((20, 20), (refused.Command, refused.ErrorCode));
    }

    [Fact(Timeout = 20_000)]
    public async Task Silent_AfterOne_NothingMoreIsAnsweredOrDone()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { FaultSpec = "silent:stage:after=1" });
        await bench.RequestAsync(1, ZaberCommand.EchoData, 0);

        await bench.SendAsync(1, ZaberCommand.MoveAbsolute, 1000);
        await bench.SendAsync(2, ZaberCommand.EchoData, 0);

        Assert.Null(await bench.TryReceiveAsync(TimeSpan.FromMinutes(2)));
        Assert.Equal(bench.Machine.Profile.X.TravelMicrosteps, bench.Machine.Stage.X.Position);
        Assert.True(bench.Machine.Faults.IsSilent(FaultTarget.Stage, 2));
    }

    [Fact(Timeout = 20_000)]
    public async Task Silent_DuringAMove_ItsCompletionReplyNeverComes()
    {
        await using var bench = MachineBench.Create();
        await bench.SendAsync(1, ZaberCommand.MoveAbsolute, 1000);
        await bench.WaitAsync(TimeSpan.FromSeconds(1));

        bench.Machine.Faults.Add("silent:stage");
        await bench.SendAsync(2, ZaberCommand.EchoData, 0);

        Assert.Null(await bench.TryReceiveAsync(TimeSpan.FromMinutes(2)));
    }

    [Fact(Timeout = 20_000)]
    public async Task Silent_OneDevice_TheOtherStillAnswers()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { FaultSpec = "silent:stage:device=2" });

        await bench.SendAsync(0, ZaberCommand.EchoData, 9);

        Assert.Equal(1, (await bench.ReceiveAsync()).Frame.Device);
        Assert.Null(await bench.TryReceiveAsync(TimeSpan.FromSeconds(1)));
    }

    [Fact(Timeout = 20_000)]
    public async Task Disconnect_AfterOne_TheHostSeesTheLinkClose()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { FaultSpec = "disconnect:stage:after=1" });
        var events = new List<SimulatorEvent>();
        bench.Machine.EventRaised += (_, e) =>
        {
            lock (events)
            {
                events.Add(e);
            }
        };
        await bench.RequestAsync(1, ZaberCommand.EchoData, 0);

        await bench.SendAsync(1, ZaberCommand.EchoData, 1);

        await Assert.ThrowsAsync<System.Threading.Channels.ChannelClosedException>(() => bench.ReceiveAsync(TimeSpan.FromMinutes(1)));
        await bench.Machine.StageServed.WaitAsync(TimeSpan.FromSeconds(5), TestContext.Current.CancellationToken);
        await Assert.ThrowsAsync<IOException>(() => bench.SendAsync(1, ZaberCommand.EchoData, 2));
        lock (events)
        {
            Assert.Contains(events, e => e.Port == "stage" && e.Message.Contains("disconnected", StringComparison.Ordinal));
            Assert.Contains(events, e => e.Port == "stage" && e.Message.Contains("fault injected: disconnect:stage", StringComparison.Ordinal));
        }
    }

    [Fact(Timeout = 20_000)]
    public async Task NoAck_AfterOne_CommandsRunButAreNotAcknowledged()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { FaultSpec = "no-ack:gate:after=1" });
        Assert.Equal("OK PONG", await bench.AskAsync("PING"));

        await bench.SendLineAsync("FREQ 1000");
        await bench.SendLineAsync("STATE?");

        Assert.Null(await bench.TryReceiveLineAsync(TimeSpan.FromSeconds(2)));

        // FREQ was carried out: the laser fired (until its watchdog, fed by nothing more, switched it off).
        Assert.Single(bench.Machine.Recorder.LaserOnIntervals(bench.Machine.NowSeconds));
    }

    [Fact(Timeout = 20_000)]
    public async Task Error_OnTheGate_RefusesAndDoesNotFire()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { FaultSpec = "error:gate:code=7" });

        Assert.Equal("ERR 7 INJECTED", await bench.AskAsync("FREQ 1000"));
        Assert.False(bench.Machine.Gate.IsFiring);
        Assert.Equal("OK FREQ 1000", await bench.AskAsync("FREQ 1000"));
    }

    [Fact(Timeout = 20_000)]
    public async Task Silent_Gate_ItsWatchdogStillSwitchesTheLaserOff()
    {
        await using var bench = MachineBench.Create();
        await bench.AskAsync("FREQ 1000");
        bench.Machine.Faults.Add("silent:gate");

        for (var i = 0; i < 4; i++)
        {
            await bench.SendLineAsync("PING");
            await bench.WaitAsync(TimeSpan.FromMilliseconds(500));
        }

        Assert.Null(await bench.TryReceiveLineAsync(TimeSpan.FromSeconds(1)));
        Assert.False(bench.Machine.Gate.IsFiring);
        Assert.Equal(1, bench.Machine.Gate.WatchdogTrips);
    }

    [Fact(Timeout = 20_000)]
    public async Task Corrupt_GateReply_ByteIsInverted()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { FaultSpec = "corrupt:gate:byte=0" });

        var line = await bench.AskAsync("PING");

        Assert.Equal((char)('O' ^ 0xFF) + "K PONG", line);
    }

    [Fact(Timeout = 20_000)]
    public async Task Delay_GateReply_ComesLater()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { FaultSpec = "delay:gate:ms=2000" });
        var sent = bench.Now;

        await bench.SendLineAsync("PING");
        var (_, at) = await bench.ReceiveLineAsync();

        Assert.InRange((at - sent).TotalSeconds, 2.0, 2.1);
    }

    [Fact(Timeout = 20_000)]
    public async Task DropReply_CountTwo_DropsTwoThenStops()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { FaultSpec = "drop-reply:gate:count=2" });

        for (var i = 0; i < 3; i++)
        {
            await bench.SendLineAsync("PING");
        }

        Assert.Equal("OK PONG", (await bench.ReceiveLineAsync()).Line);
        Assert.Null(await bench.TryReceiveLineAsync(TimeSpan.FromSeconds(1)));
        Assert.Equal(2, bench.Machine.Faults.TriggeredCount);
    }

    [Fact(Timeout = 20_000)]
    public async Task Clear_AtRunTime_LiftsSilence()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { FaultSpec = "silent:stage" });
        await bench.SendAsync(1, ZaberCommand.EchoData, 1);
        Assert.Null(await bench.TryReceiveAsync(TimeSpan.FromSeconds(1)));

        bench.Machine.Faults.Clear();

        Assert.Equal(2, (await bench.RequestAsync(1, ZaberCommand.EchoData, 2)).Data);
    }
}
