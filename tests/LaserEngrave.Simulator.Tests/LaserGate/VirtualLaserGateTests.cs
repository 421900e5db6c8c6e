using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator.Burn;

namespace LaserEngrave.Simulator.Tests.LaserGate;

/// <summary>The gate's ASCII protocol (docs/laser-gate-protocol.md), line by line.</summary>
public class VirtualLaserGateTests
{
    /// <summary>One byte at 9600 baud 8N1.</summary>
    private static readonly TimeSpan ByteTime = TimeSpan.FromTicks(10_417);

    [Fact(Timeout = 20_000)]
    public async Task Identify_RepliesPicGateAndFirmware()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { GateFirmware = "7.3" });

        Assert.Equal("OK PICGATE 7.3", await bench.AskAsync("*IDN?"));
    }

    [Fact(Timeout = 20_000)]
    public async Task Freq_InRange_FiresAndStateSaysSo()
    {
        await using var bench = MachineBench.Create();

        var ack = await bench.AskAsync("FREQ 1000");
        var state = await bench.AskAsync("STATE?");

        Assert.Equal("OK FREQ 1000", ack);
        Assert.Equal("OK STATE 1000 ON WDOG 1000", state);
        Assert.True(bench.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 20_000)]
    public async Task Off_AfterFreq_StopsFiring()
    {
        await using var bench = MachineBench.Create();
        await bench.AskAsync("FREQ 2500");

        var ack = await bench.AskAsync("OFF");

        Assert.Equal("OK FREQ 0", ack);
        Assert.Equal("OK STATE 0 OFF WDOG 1000", await bench.AskAsync("STATE?"));
    }

    [Fact(Timeout = 20_000)]
    public async Task FreqZero_StopsFiring()
    {
        await using var bench = MachineBench.Create();
        await bench.AskAsync("FREQ 2500");

        Assert.Equal("OK FREQ 0", await bench.AskAsync("FREQ 0"));
        Assert.False(bench.Machine.Gate.IsFiring);
    }

    [Theory(Timeout = 20_000)]
    [InlineData("FREQ 100001", "ERR 2 RANGE")]
    [InlineData("FREQ -1", "ERR 2 RANGE")]
    [InlineData("FREQ abc", "ERR 3 SYNTAX")]
    [InlineData("FREQ 10.5", "ERR 3 SYNTAX")]
    [InlineData("FREQ", "ERR 3 SYNTAX")]
    [InlineData("WDOG 49", "ERR 2 RANGE")]
    [InlineData("WDOG 60001", "ERR 2 RANGE")]
    [InlineData("BURST 0 1000", "ERR 2 RANGE")]
    [InlineData("BURST 10", "ERR 3 SYNTAX")]
    [InlineData("FIRE", "ERR 1 UNKNOWN")]
    [InlineData("HELLO WORLD", "ERR 1 UNKNOWN")]
    public async Task BadCommand_RepliesTheDocumentedError(string line, string reply)
    {
        await using var bench = MachineBench.Create();

        Assert.Equal(reply, await bench.AskAsync(line));
        Assert.False(bench.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 20_000)]
    public async Task Line_CrLfAndLowerCase_AreAccepted()
    {
        await using var bench = MachineBench.Create();

        Assert.Equal("OK FREQ 10", await bench.AskAsync("freq 10\r"));
    }

    [Fact(Timeout = 20_000)]
    public async Task Line_TooLong_AnsweredAsUnknown()
    {
        await using var bench = MachineBench.Create();

        Assert.Equal("ERR 1 UNKNOWN", await bench.AskAsync("FREQ " + new string('1', 300)));
        Assert.Equal("OK PONG", await bench.AskAsync("PING"));
    }

    [Fact(Timeout = 20_000)]
    public async Task Ping_RepliesPong_AfterBothLinesTimeOnTheWire()
    {
        await using var bench = MachineBench.Create();
        var sent = bench.Now;

        await bench.SendLineAsync("PING");
        var (line, at) = await bench.ReceiveLineAsync();

        Assert.Equal("OK PONG", line);

        // "PING\n" is 5 bytes in, "OK PONG\n" 8 bytes out.
        var expected = TimeSpan.FromSeconds(13 * 10 / 9600.0);
        Assert.True(Math.Abs((at - sent - expected).Ticks) <= 3, $"expected {expected}, got {at - sent}");
    }

    [Fact(Timeout = 20_000)]
    public async Task Wdog_Valid_SetsTheWatchdog()
    {
        await using var bench = MachineBench.Create();

        Assert.Equal("OK WDOG 250", await bench.AskAsync("WDOG 250"));
        Assert.Equal("OK STATE 0 OFF WDOG 250", await bench.AskAsync("STATE?"));
        Assert.Equal("OK WDOG 0", await bench.AskAsync("WDOG 0"));
    }

    [Fact(Timeout = 20_000)]
    public async Task Watchdog_SilenceWhileFiring_SwitchesOffAfterTheWatchdogTime()
    {
        await using var bench = MachineBench.Create();
        var sent = bench.Now;
        await bench.AskAsync("FREQ 1000");

        await bench.WaitAsync(TimeSpan.FromSeconds(3));
        var state = await bench.AskAsync("STATE?");
        var again = await bench.AskAsync("STATE?");

        Assert.Equal("OK STATE 0 OFF WDOG 1000 TRIPPED", state);
        Assert.Equal("OK STATE 0 OFF WDOG 1000", again);
        Assert.Equal(1, bench.Machine.Gate.WatchdogTrips);

        // On from the moment "FREQ 1000\n" (10 bytes) arrived, off exactly one watchdog time later.
        var onAt = (sent + (10 * ByteTime)).TotalSeconds;
        var (from, to) = Assert.Single(bench.Machine.Recorder.LaserOnIntervals(bench.Machine.NowSeconds));
        Assert.Equal(onAt, from, 4);
        Assert.Equal(onAt + 1.0, to, 4);
    }

    [Fact(Timeout = 20_000)]
    public async Task Watchdog_PingsKeepComing_LaserStaysOn()
    {
        await using var bench = MachineBench.Create();
        await bench.AskAsync("FREQ 1000");

        for (var i = 0; i < 10; i++)
        {
            await bench.WaitAsync(TimeSpan.FromMilliseconds(600));
            Assert.Equal("OK PONG", await bench.AskAsync("PING"));
        }

        Assert.True(bench.Machine.Gate.IsFiring);
        Assert.Equal("OK STATE 1000 ON WDOG 1000", await bench.AskAsync("STATE?"));
    }

    [Fact(Timeout = 20_000)]
    public async Task Watchdog_InvalidLinesAlsoFeedIt()
    {
        await using var bench = MachineBench.Create();
        await bench.AskAsync("FREQ 1000");

        for (var i = 0; i < 5; i++)
        {
            await bench.WaitAsync(TimeSpan.FromMilliseconds(900));
            Assert.Equal("ERR 1 UNKNOWN", await bench.AskAsync("NONSENSE"));
        }

        Assert.True(bench.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 20_000)]
    public async Task Watchdog_Disabled_LaserStaysOnThroughSilence()
    {
        await using var bench = MachineBench.Create();
        await bench.AskAsync("WDOG 0");
        await bench.AskAsync("FREQ 1000");

        await bench.WaitAsync(TimeSpan.FromMinutes(2));

        Assert.True(bench.Machine.Gate.IsFiring);
        Assert.Equal(0, bench.Machine.Gate.WatchdogTrips);
    }

    [Fact(Timeout = 20_000)]
    public async Task Burst_FiresItsPulsesThenStopsByItself()
    {
        await using var bench = MachineBench.Create();

        Assert.Equal("OK BURST 250", await bench.AskAsync("BURST 250 1000"));
        Assert.True(bench.Machine.Gate.IsFiring);
        await bench.WaitAsync(TimeSpan.FromSeconds(1));

        Assert.False(bench.Machine.Gate.IsFiring);
        var (from, to) = Assert.Single(bench.Machine.Recorder.LaserOnIntervals(bench.Machine.NowSeconds));
        Assert.Equal(0.25, to - from, 6);
        Assert.Equal("OK STATE 0 OFF WDOG 1000", await bench.AskAsync("STATE?"));
    }

    [Theory(Timeout = 20_000)]
    [InlineData(1, 1000)]
    [InlineData(10, 1000)]
    [InlineData(7, 3000)]
    [InlineData(250, 60000)]
    public async Task Burst_Repeated_FiresExactlyItsPulsesEachTime(int pulses, int hz)
    {
        await using var bench = MachineBench.Create();

        // At many start instants: a burst timed by a clock rounded to whole ticks must still count N pulses.
        const int Bursts = 20;
        for (var i = 0; i < Bursts; i++)
        {
            await bench.AskAsync($"BURST {pulses} {hz}");
            await bench.WaitAsync(TimeSpan.FromMilliseconds(3.3 + ((double)pulses * 1000 / hz)));
        }

        var report = bench.Machine.Recorder.Analyze(new BurnGrid(0, 0, 1000, 10, 10));
        Assert.Equal(Bursts * pulses, report.Pulses);
    }

    [Fact(Timeout = 20_000)]
    public async Task Burst_OffDuringIt_StopsAtOnce()
    {
        await using var bench = MachineBench.Create();
        await bench.AskAsync("BURST 100000 1000");

        await bench.WaitAsync(TimeSpan.FromMilliseconds(500));
        await bench.AskAsync("OFF");
        await bench.WaitAsync(TimeSpan.FromMinutes(5));

        var (from, to) = Assert.Single(bench.Machine.Recorder.LaserOnIntervals(bench.Machine.NowSeconds));
        Assert.InRange(to - from, 0.5, 0.6);
    }

    [Theory(Timeout = 20_000)]
    [InlineData(300)]
    [InlineData(1000)]
    [InlineData(5000)]
    [InlineData(20000)]
    public async Task BurstAfter_Delay_FirstPulseThatLongAfterTheLineArrived(int afterUs)
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { GateProcessing = null });
        var text = $"BURST 120 1000 AFTER {afterUs}";
        var sent = bench.Now;

        Assert.Equal($"OK BURST 120 AFTER {afterUs}", await bench.AskAsync(text));
        await bench.WaitAsync(TimeSpan.FromSeconds(1));

        // The line's last byte arrived (text.Length + 1) bytes after the write; the gate's own timer does the rest.
        var arrived = sent.TotalSeconds + ((text.Length + 1) * 10.0 / 9600);
        var (from, to) = Assert.Single(bench.Machine.Recorder.LaserOnIntervals(bench.Machine.NowSeconds));
        Assert.Equal(arrived + (afterUs / 1e6), from, 6);
        Assert.Equal(0.120, to - from, 6);
    }

    [Fact(Timeout = 20_000)]
    public async Task BurstAfter_Accepted_AcknowledgedBeforeTheFirstPulseAndStateOn()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { GateProcessing = null });

        await bench.SendLineAsync("BURST 10 1000 AFTER 50000");
        var (ack, at) = await bench.ReceiveLineAsync();
        var state = await bench.AskAsync("STATE?");
        var firingWhileWaiting = bench.Machine.Gate.IsFiring;
        await bench.WaitAsync(TimeSpan.FromSeconds(1));

        Assert.Equal("OK BURST 10 AFTER 50000", ack);
        Assert.Equal("OK STATE 1000 ON WDOG 1000", state);
        Assert.False(firingWhileWaiting);
        var (from, _) = Assert.Single(bench.Machine.Recorder.LaserOnIntervals(bench.Machine.NowSeconds));
        Assert.True(at.TotalSeconds < from, $"acknowledged at {at.TotalSeconds} s, first pulse at {from} s");
    }

    [Theory(Timeout = 20_000)]
    [InlineData("OFF")]
    [InlineData("FREQ 0")]
    public async Task BurstAfter_FrequencyCommandWhileWaiting_NeverFires(string command)
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { GateProcessing = null });

        await bench.AskAsync("BURST 10 1000 AFTER 100000");
        await bench.AskAsync(command);
        await bench.WaitAsync(TimeSpan.FromSeconds(1));

        Assert.Empty(bench.Machine.Recorder.LaserOnIntervals(bench.Machine.NowSeconds));
        Assert.Equal("OK STATE 0 OFF WDOG 1000", await bench.AskAsync("STATE?"));
    }

    [Fact(Timeout = 20_000)]
    public async Task BurstAfter_WatchdogTripsWhileWaiting_NeverFires()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { GateProcessing = null });
        await bench.AskAsync("WDOG 50");

        await bench.AskAsync("BURST 10 1000 AFTER 1000000");
        await bench.WaitAsync(TimeSpan.FromSeconds(2));

        Assert.Empty(bench.Machine.Recorder.LaserOnIntervals(bench.Machine.NowSeconds));
        Assert.Equal("OK STATE 0 OFF WDOG 50 TRIPPED", await bench.AskAsync("STATE?"));
        Assert.Equal(1, bench.Machine.Gate.WatchdogTrips);
    }

    [Fact(Timeout = 20_000)]
    public async Task BurstAfter_ShorterThanTheProcessing_FiresWhenTheGateCan()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { GateProcessing = null });
        var sent = bench.Now;

        await bench.AskAsync("BURST 3 1000 AFTER 0");
        await bench.WaitAsync(TimeSpan.FromSeconds(1));

        var arrived = sent.TotalSeconds + (21 * 10.0 / 9600);
        var (from, _) = Assert.Single(bench.Machine.Recorder.LaserOnIntervals(bench.Machine.NowSeconds));
        Assert.InRange(from - arrived, 100e-6, 300e-6);
    }

    [Theory(Timeout = 20_000)]
    [InlineData("BURST 5 1000 AFTER 1000001", "ERR 2 RANGE")]
    [InlineData("BURST 5 1000 AFTER -1", "ERR 2 RANGE")]
    [InlineData("BURST 0 1000 AFTER 300", "ERR 2 RANGE")]
    [InlineData("BURST 5 1000 AFTER x", "ERR 3 SYNTAX")]
    [InlineData("BURST 5 1000 LATER 300", "ERR 3 SYNTAX")]
    [InlineData("burst 5 1000 after 300", "OK BURST 5 AFTER 300")]
    [InlineData("CAPS?", "OK CAPS AFTER")]
    public async Task BurstAfter_Lines_AnsweredAsTheFirmware(string line, string reply)
    {
        await using var bench = MachineBench.Create();

        Assert.Equal(reply, await bench.AskAsync(line));
    }

    [Fact(Timeout = 20_000)]
    public async Task Profile_OtherCommandStrings_TheGateSpeaksThem()
    {
        var profile = MachineProfile.Default with
        {
            Gate = new LaserGateProfile { FrequencyCommand = "SETF {0} HZ", OffCommand = "STOP", AckPrefix = "ACK", ErrorPrefix = "NAK" },
        };
        await using var bench = MachineBench.Create(profile: profile);

        Assert.Equal("ACK FREQ 400", await bench.AskAsync("SETF 400 HZ"));
        Assert.Equal("ACK FREQ 0", await bench.AskAsync("STOP"));
        Assert.Equal("NAK 1 UNKNOWN", await bench.AskAsync("FREQ 400"));
    }
}
