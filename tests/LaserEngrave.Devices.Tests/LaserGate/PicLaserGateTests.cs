using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.LaserGate;
using LaserEngrave.Devices.Tests.Fakes;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Serial;
using Microsoft.Extensions.Time.Testing;

namespace LaserEngrave.Devices.Tests.LaserGate;

/// <summary>The gate host against <see cref="FakeLaserGate"/>. Tests in which time never moves stand on a
/// <c>FakeTimeProvider</c>; tests about timing, ordering or what the reader does in between run on the simulation's loop.</summary>
public class PicLaserGateTests
{
    private const string Port = "/dev/fake-gate";
    private static readonly CancellationToken None = CancellationToken.None;

    [Fact]
    public async Task IdentifyAsync_GateAnswers_ReturnsTheTextAfterOk()
    {
        await using var rig = new GateRig(new FakeTimeProvider());
        rig.Fake.Firmware = "PICGATE 2.1";

        Assert.Equal("PICGATE 2.1", await rig.Gate.IdentifyAsync(None).Within());
        Assert.Equal("*IDN?", await rig.Fake.NextAsync());
    }

    [Fact]
    public async Task SetFrequencyAsync_1kHz_SendsFreqLineAndWaitsForOk()
    {
        await using var rig = new GateRig(new FakeTimeProvider());

        await rig.Gate.SetFrequencyAsync(1000, None).Within();

        Assert.Equal("FREQ 1000", await rig.Fake.NextAsync());
        Assert.Equal(1000, rig.Fake.FrequencyHz);
    }

    [Fact]
    public async Task OffAsync_AfterFiring_StopsTheGate()
    {
        await using var rig = new GateRig(new FakeTimeProvider());
        await rig.Gate.SetFrequencyAsync(1000, None).Within();

        await rig.Gate.OffAsync(None).Within();

        Assert.Equal(0, rig.Fake.FrequencyHz);
    }

    [Theory]
    [InlineData("OK STATE 1000 ON WDOG 800", 1000, true, 800, false)]
    [InlineData("OK STATE 0 OFF WDOG 0 TRIPPED", 0, false, 0, true)]
    public async Task GetStateAsync_StateLine_IsParsed(string reply, int hz, bool firing, int watchdogMs, bool tripped)
    {
        await using var rig = new GateRig(new FakeTimeProvider());
        rig.Fake.Intercept = _ => reply + "\n";

        var state = await rig.Gate.GetStateAsync(None).Within();

        Assert.Equal(new LaserGateState(hz, firing, watchdogMs, tripped), state);
    }

    [Fact]
    public async Task GetStateAsync_AfterSettingUp_ReflectsTheGate()
    {
        await using var rig = new GateRig(new FakeTimeProvider());
        await rig.Gate.SetWatchdogAsync(750, None).Within();
        await rig.Gate.SetFrequencyAsync(2500, None).Within();

        Assert.Equal(new LaserGateState(2500, true, 750, false), await rig.Gate.GetStateAsync(None).Within());
    }

    [Theory]
    [InlineData("OK STATE 1000 MAYBE WDOG 800")]
    [InlineData("OK STATE fast ON WDOG 800")]
    public async Task GetStateAsync_UnreadableState_ThrowsNamingTheReply(string reply)
    {
        await using var rig = new GateRig(new FakeTimeProvider());
        rig.Fake.Intercept = _ => reply + "\n";

        var error = await Assert.ThrowsAsync<LaserGateException>(() => rig.Gate.GetStateAsync(None).Within());

        Assert.Contains($"laser gate on {Port}: cannot read the state", error.Message, StringComparison.Ordinal);
        Assert.Contains(reply[3..], error.Message, StringComparison.Ordinal);
    }

    [Fact]
    public async Task GetStateAsync_ReplyToAnotherCommand_IsReportedAndDoesNotAnswer()
    {
        await using var rig = new GateRig(new VirtualTimeProvider());
        var unexpected = new List<string>();
        rig.Gate.UnexpectedLine += (_, e) => unexpected.Add(e.Line);
        rig.Fake.Intercept = _ => "OK 1000 ON\n";

        await rig.RunAsync(async () =>
        {
            var state = rig.Gate.GetStateAsync(None);
            await rig.Time.SettleAsync();
            Assert.Equal(["OK 1000 ON"], unexpected);
            Assert.False(state.IsCompleted);

            await VirtualTime.ThrowsAsync<DeviceTimeoutException>(state);

            Assert.Equal(TimeSpan.FromMilliseconds(500), rig.Time.Elapsed);
            Assert.Equal(["OK 1000 ON"], unexpected);
        });
    }

    [Fact]
    public async Task SetFrequencyAsync_GateSaysErr_ThrowsWithTheGatesText()
    {
        await using var rig = new GateRig(new FakeTimeProvider());

        var error = await Assert.ThrowsAsync<LaserGateException>(() => rig.Gate.SetFrequencyAsync(200000, None).Within());

        Assert.Equal($"laser gate on {Port} refused 'FREQ 200000': ERR 2 RANGE", error.Message);
        Assert.Equal("FREQ 200000", error.Command);
    }

    [Fact]
    public async Task SendAsync_ReplyWithNeitherPrefix_ThrowsSayingWhatWasExpected()
    {
        await using var rig = new GateRig(new FakeTimeProvider());
        rig.Fake.Intercept = _ => "HELLO\n";

        var error = await Assert.ThrowsAsync<LaserGateException>(() => rig.Gate.KeepAliveAsync(None).Within());

        Assert.Contains("answered 'PING' with 'HELLO'", error.Message, StringComparison.Ordinal);
    }

    [Fact]
    public async Task SetFrequencyAsync_SilentGate_TimesOutOnTheClockWithAClearMessage()
    {
        await using var rig = new GateRig(new VirtualTimeProvider());
        rig.Fake.Intercept = _ => string.Empty;

        await rig.RunAsync(async () =>
        {
            var command = rig.Gate.SetFrequencyAsync(1000, None);
            Assert.Equal("FREQ 1000", await rig.Fake.NextAsync());
            var sentAt = rig.Time.Elapsed;

            var error = await VirtualTime.ThrowsAsync<DeviceTimeoutException>(command);

            Assert.Equal(TimeSpan.FromMilliseconds(500), rig.Time.Elapsed - sentAt);
            Assert.Equal($"laser gate on {Port} did not acknowledge 'FREQ 1000' within 500 ms", error.Message);
        });
    }

    [Fact]
    public async Task Profile_OverriddenCommandsAndPrefixes_AreUsed()
    {
        var profile = new LaserGateProfile
        {
            FrequencyCommand = "F{0}",
            OffCommand = "F0",
            AckPrefix = "ACK",
            ErrorPrefix = "NAK",
            LineTerminator = "\r\n",
        };
        await using var rig = new GateRig(new FakeTimeProvider(), profile);
        rig.Fake.Intercept = line => line switch
        {
            "F1000" => "ACK\r\n",
            "F0" => "ACK\r\n",
            _ => "NAK what\r\n",
        };

        await rig.Gate.SetFrequencyAsync(1000, None).Within();
        await rig.Gate.OffAsync(None).Within();
        var error = await Assert.ThrowsAsync<LaserGateException>(() => rig.Gate.KeepAliveAsync(None).Within());

        Assert.Equal("F1000", await rig.Fake.NextAsync());
        Assert.Equal("F0", await rig.Fake.NextAsync());
        Assert.Contains("refused 'PING': NAK what", error.Message, StringComparison.Ordinal);
    }

    [Fact]
    public async Task SendAsync_ReplyInPiecesEndedByCrLf_IsOneLine()
    {
        await using var rig = new GateRig(new FakeTimeProvider());
        rig.Fake.Intercept = _ => string.Empty;
        var identify = rig.Gate.IdentifyAsync(None);
        await rig.Fake.NextAsync();

        await rig.Fake.SendRawAsync("OK PIC");
        await rig.Fake.SendRawAsync("GATE 3\r");
        await rig.Fake.SendRawAsync("\n");

        Assert.Equal("PICGATE 3", await identify.Within());
    }

    [Fact]
    public async Task UnexpectedLine_WithNoCommandWaiting_IsReportedAndNotTakenAsTheNextReply()
    {
        await using var rig = new GateRig(new VirtualTimeProvider());
        var stray = new List<string>();
        rig.Gate.UnexpectedLine += (_, e) => stray.Add(e.Line);

        await rig.RunAsync(async () =>
        {
            await rig.Fake.SendRawAsync("OK LATE\n");
            await rig.Time.SettleAsync();
            Assert.Equal(["OK LATE"], stray);

            Assert.Equal("PICGATE 1.0", await rig.Gate.IdentifyAsync(None));
            Assert.Equal(["OK LATE"], stray);
        });
    }

    [Fact]
    public async Task SendAsync_TwoCommandsAtOnce_BothGoOutAndEachGetsTheReplyThatAnswersIt()
    {
        await using var rig = new GateRig(new VirtualTimeProvider());
        rig.Fake.Intercept = _ => string.Empty;

        await rig.RunAsync(async () =>
        {
            var first = rig.Gate.SetFrequencyAsync(1000, None);
            Assert.Equal("FREQ 1000", await rig.Fake.NextAsync());
            var second = rig.Gate.OffAsync(None);
            Assert.Equal("OFF", await rig.Fake.NextAsync());
            Assert.False(first.IsCompleted);
            Assert.False(second.IsCompleted);

            // Replies in order: the switch-on's first, then the switch-off's; neither answers the other.
            await rig.Fake.SendRawAsync("OK FREQ 1000\n");
            await first;
            Assert.False(second.IsCompleted);
            await rig.Fake.SendRawAsync("OK FREQ 0\n");

            await Task.WhenAll(first, second);
            Assert.Equal(TimeSpan.Zero, rig.Time.Elapsed);
        });
    }

    [Fact]
    public async Task EmergencyAsync_AfterATimeoutWithAKeepAliveUnanswered_GoesOutAtOnceWithoutAPingAhead()
    {
        // Issue 31: after a timeout every ordinary command waits for a PING's answer first; the emergency off must not.
        await using var rig = new GateRig(new VirtualTimeProvider());
        rig.Fake.Intercept = _ => string.Empty;

        await rig.RunAsync(async () =>
        {
            var off = rig.Gate.OffAsync(None);
            Assert.Equal("OFF", await rig.Fake.NextAsync());
            await VirtualTime.ThrowsAsync<DeviceTimeoutException>(off);

            // An ordinary command now gets the link back in step first, and holds its turn while the PING is unanswered.
            var ordinary = rig.Gate.SetFrequencyAsync(0, None);
            Assert.Equal("PING", await rig.Fake.NextAsync());
            var sentAt = rig.Time.Elapsed;

            var emergency = new[] { EmergencyCommand.Off, EmergencyCommand.FrequencyZero, EmergencyCommand.ShortestWatchdog }
                .Select(c => rig.Gate.EmergencyAsync(c, None)).ToList();
            Assert.Equal("OFF", await rig.Fake.NextAsync());
            Assert.Equal("FREQ 0", await rig.Fake.NextAsync());
            Assert.Equal("WDOG 50", await rig.Fake.NextAsync());
            Assert.Equal(sentAt, rig.Time.Elapsed);

            await rig.Fake.SendRawAsync("OK FREQ 0\nOK FREQ 0\nOK WDOG 50\n");
            await Task.WhenAll(emergency);
            Assert.False(ordinary.IsCompleted);
            await VirtualTime.ThrowsAsync<DeviceTimeoutException>(ordinary);
        });
    }

    [Fact]
    public async Task EmergencyAsync_WhileASwitchOnWaitsBehindAResync_TheSwitchOnIsNeverWrittenAfterIt()
    {
        // A switch-on held up behind the PING must not reach the gate after the emergency off (GRBL's reset flushes its queue).
        await using var rig = new GateRig(new VirtualTimeProvider());
        rig.Fake.Intercept = _ => string.Empty;

        await rig.RunAsync(async () =>
        {
            var first = rig.Gate.OffAsync(None);
            Assert.Equal("OFF", await rig.Fake.NextAsync());
            await VirtualTime.ThrowsAsync<DeviceTimeoutException>(first);
            var on = rig.Gate.SetFrequencyAsync(1000, None);
            Assert.Equal("PING", await rig.Fake.NextAsync());

            var off = rig.Gate.EmergencyAsync(EmergencyCommand.Off, None);
            Assert.Equal("OFF", await rig.Fake.NextAsync());
            await rig.Fake.SendRawAsync("OK PONG\nOK FREQ 0\n");
            await off;

            var dropped = await Assert.ThrowsAsync<DeviceException>(() => on);
            Assert.Contains("'FREQ 1000' was not sent: the emergency off went first", dropped.Message, StringComparison.Ordinal);
            Assert.DoesNotContain("FREQ 1000", rig.Fake.AllReceived());
        });
    }

    [Fact]
    public async Task CloseAsync_WithACommandWaiting_FailsItAndEveryLaterOne()
    {
        await using var rig = new GateRig(new FakeTimeProvider());
        rig.Fake.Intercept = _ => string.Empty;
        var command = rig.Gate.SetFrequencyAsync(1000, None);
        await rig.Fake.NextAsync();

        await rig.Gate.CloseAsync();

        await Assert.ThrowsAsync<LinkLostException>(() => command.Within());
        await Assert.ThrowsAsync<LinkLostException>(() => rig.Gate.EmergencyAsync(EmergencyCommand.Off, None).Within());
        Assert.False(rig.Gate.IsOpen);
    }

    [Fact]
    public async Task SendAsync_LinkDropsWhileWaiting_ThrowsLinkLostNamingPortAndCommand()
    {
        await using var rig = new GateRig(new FakeTimeProvider());
        rig.Fake.Intercept = _ => string.Empty;
        var command = rig.Gate.SetFrequencyAsync(1000, None);
        await rig.Fake.NextAsync();

        await rig.Fake.DisposeAsync();

        var error = await Assert.ThrowsAsync<LinkLostException>(() => command.Within());
        Assert.Equal($"laser gate on {Port}: the link was lost while waiting for the reply to 'FREQ 1000'", error.Message);
        var next = await Assert.ThrowsAsync<LinkLostException>(() => rig.Gate.OffAsync(None).Within());
        Assert.Contains("cannot send 'OFF'", next.Message, StringComparison.Ordinal);
    }

    [Fact]
    public async Task SetFrequencyAsync_Negative_IsRefusedBeforeSending()
    {
        await using var rig = new GateRig(new FakeTimeProvider());

        await Assert.ThrowsAsync<ArgumentOutOfRangeException>(() => rig.Gate.SetFrequencyAsync(-1, None));
    }

    [Fact]
    public async Task BurstAsync_SendsPulseCountAndFrequency()
    {
        await using var rig = new GateRig(new FakeTimeProvider());

        await rig.Gate.BurstAsync(10, 500, None).Within();

        Assert.Equal("BURST 10 500", await rig.Fake.NextAsync());
    }

    /// <summary>The gate and its fake on <paramref name="clock"/>: on the loop of a <see cref="VirtualTimeProvider"/>, or on the thread pool.</summary>
    private sealed class GateRig : IAsyncDisposable
    {
        public GateRig(TimeProvider clock, LaserGateProfile? profile = null)
        {
            Clock = clock;
            var (host, device) = InMemorySerialLink.CreatePair(Port);
            Fake = new FakeLaserGate(device, Clock);
            Gate = new PicLaserGate(host, profile ?? new LaserGateProfile(), Clock);
        }

        public TimeProvider Clock { get; }

        /// <summary>The virtual clock (only for a rig made on one).</summary>
        public VirtualTimeProvider Time => (VirtualTimeProvider)Clock;

        public FakeLaserGate Fake { get; }

        public PicLaserGate Gate { get; }

        /// <summary>Runs the test's body: as one operation on the loop of a virtual clock, directly on a fake one.</summary>
        public Task RunAsync(Func<Task> body) => Clock.RunTestAsync(body);

        public async ValueTask DisposeAsync()
        {
            await Clock.RunTestAsync(async () =>
            {
                await Gate.DisposeAsync();
                await Fake.DisposeAsync();
            });
            (Clock as IDisposable)?.Dispose();
        }
    }
}
