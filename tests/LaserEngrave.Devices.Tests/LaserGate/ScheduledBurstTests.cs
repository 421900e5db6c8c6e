using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.LaserGate;
using LaserEngrave.Devices.Tests.Execution;
using LaserEngrave.Devices.Tests.Fakes;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Devices.Tests.LaserGate;

/// <summary>The host's scheduled burst (BURST n hz AFTER us) and CAPS? against the twin's gate, in virtual time. The run
/// engine does not send it yet; these prove the link's half.</summary>
public class ScheduledBurstTests
{
    private static readonly CancellationToken None = CancellationToken.None;

    [Fact(Timeout = 30_000)]
    public async Task BurstAfterAsync_TwinGate_AcknowledgedAndFirstPulseAtTheDelay()
    {
        await using var run = SimulatedRun.Create(new SimulatorOptions { AdapterLatency = Jitter.None });

        await run.Do(async () =>
        {
            await run.Gate.BurstAfterAsync(120, 1000, 5000, None);
            await Task.Delay(TimeSpan.FromSeconds(1), run.Time);
        });

        var (line, at) = Assert.Single(run.Written.Where(w => w.Port == "gate").Select(w => (w.Line, w.Seconds)));
        Assert.Equal("BURST 120 1000 AFTER 5000", line);
        var (from, to) = Assert.Single(run.Machine.Recorder.LaserOnIntervals(run.Machine.NowSeconds));
        var arrived = at + ((line.Length + 1) * 10.0 / 9600);
        Assert.Equal(arrived + 0.005, from, 6);
        Assert.Equal(0.120, to - from, 6);
    }

    [Fact(Timeout = 30_000)]
    public async Task GetCapabilitiesAsync_TwinGate_ListsAfter()
    {
        await using var run = SimulatedRun.Create();

        var caps = await run.Do(() => run.Gate.GetCapabilitiesAsync(None));

        Assert.Contains(LaserGateCapabilities.After, caps);
    }

    [Fact(Timeout = 30_000)]
    public async Task BurstAfterAsync_ProfileStrings_SentAndMatchedAsTheProfileSays()
    {
        var profile = MachineProfile.Default with
        {
            Gate = new LaserGateProfile { BurstAfterCommand = "BURST {0} {1} AT {2}", BurstAfterReply = "BURST {0} AT {2}" },
        };
        await using var run = SimulatedRun.Create(profile: profile);

        await run.Do(() => run.Gate.BurstAfterAsync(3, 1000, 700, None));

        Assert.Contains(run.Written, w => w.Port == "gate" && w.Line == "BURST 3 1000 AT 700");
    }

    [Fact]
    public async Task GetCapabilitiesAsync_OlderGateRefuses_None()
    {
        var (host, device) = InMemorySerialLink.CreatePair("/dev/fake-gate");
        var clock = new Microsoft.Extensions.Time.Testing.FakeTimeProvider();
        await using var fake = new FakeLaserGate(device, clock) { Intercept = _ => "ERR 1 UNKNOWN\n" };
        await using var gate = new PicLaserGate(host, new LaserGateProfile(), clock);

        var caps = await gate.GetCapabilitiesAsync(None).Within();

        Assert.Empty(caps);
    }

    [Fact]
    public async Task BurstAfterAsync_OlderGateRefuses_ThrowsNamingTheCommand()
    {
        var (host, device) = InMemorySerialLink.CreatePair("/dev/fake-gate");
        var clock = new Microsoft.Extensions.Time.Testing.FakeTimeProvider();
        await using var fake = new FakeLaserGate(device, clock) { Intercept = _ => "ERR 3 SYNTAX\n" };
        await using var gate = new PicLaserGate(host, new LaserGateProfile(), clock);

        var error = await Assert.ThrowsAsync<LaserGateException>(() => gate.BurstAfterAsync(5, 1000, 300, None).Within());

        Assert.Contains("BURST 5 1000 AFTER 300", error.Message, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData(-1)]
    [InlineData(1_000_001)]
    public async Task BurstAfterAsync_DelayOutOfRange_ThrowsBeforeSending(int afterUs)
    {
        var (host, _) = InMemorySerialLink.CreatePair("/dev/fake-gate");
        await using var gate = new PicLaserGate(host, new LaserGateProfile(), new Microsoft.Extensions.Time.Testing.FakeTimeProvider());

        await Assert.ThrowsAsync<ArgumentOutOfRangeException>(() => gate.BurstAfterAsync(5, 1000, afterUs, None));
    }
}
