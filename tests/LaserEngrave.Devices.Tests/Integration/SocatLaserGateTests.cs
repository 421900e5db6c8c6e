using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.LaserGate;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Devices.Tests.Fakes;

namespace LaserEngrave.Devices.Tests.Integration;

/// <summary>The laser gate host over a real pty (SerialPortLink on both ends of a socat pair), in real time.</summary>
public sealed class SocatLaserGateTests : IAsyncDisposable
{
    private readonly SocatPair _pair = new();
    private readonly FakeLaserGate _fake;
    private readonly PicLaserGate _gate;

    public SocatLaserGateTests()
    {
        _fake = new FakeLaserGate(SerialPortLink.Open(_pair.B));
        _gate = PicLaserGate.Open(_pair.A, new LaserGateProfile { TimeoutMs = 1000 }, TimeProvider.System);
    }

    private static CancellationToken Token => TestContext.Current.CancellationToken;

    [Fact]
    public async Task IdentifyOnStatusOff_OverAPty_WorkEndToEnd()
    {
        Assert.Equal("PICGATE 1.0", await _gate.IdentifyAsync(Token).Within());

        await _gate.SetWatchdogAsync(1000, Token).Within();
        await _gate.SetFrequencyAsync(1000, Token).Within();
        Assert.Equal(new LaserGateState(1000, true, 1000, false), await _gate.GetStateAsync(Token).Within());

        await _gate.OffAsync(Token).Within();
        Assert.Equal(new LaserGateState(0, false, 1000, false), await _gate.GetStateAsync(Token).Within());
    }

    [Fact]
    public async Task SetFrequencyAsync_OutOfRange_GateErrorReachesTheHost()
    {
        var error = await Assert.ThrowsAsync<LaserGateException>(() => _gate.SetFrequencyAsync(250000, Token).Within());

        Assert.Equal($"laser gate on {_pair.A} refused 'FREQ 250000': ERR 2 RANGE", error.Message);
    }

    [Fact]
    public async Task SetFrequencyAsync_SilentGate_TimesOut()
    {
        _fake.Intercept = _ => string.Empty;

        var error = await Assert.ThrowsAsync<DeviceTimeoutException>(() => _gate.SetFrequencyAsync(1000, Token).Within());

        Assert.Equal($"laser gate on {_pair.A} did not acknowledge 'FREQ 1000' within 1000 ms", error.Message);
    }

    [Fact]
    public async Task KeepAliveAsync_CableGone_LinkLost()
    {
        _fake.Intercept = _ => string.Empty;
        var ping = _gate.KeepAliveAsync(Token);
        await _fake.NextAsync();

        _pair.Kill();

        var error = await Assert.ThrowsAsync<LinkLostException>(() => ping.Within());
        Assert.StartsWith($"laser gate on {_pair.A}: the link was lost while waiting for the reply to 'PING'", error.Message, StringComparison.Ordinal);
    }

    public async ValueTask DisposeAsync()
    {
        await _gate.DisposeAsync().AsTask().Within();
        await _fake.DisposeAsync().AsTask().Within();
        _pair.Dispose();
    }
}
