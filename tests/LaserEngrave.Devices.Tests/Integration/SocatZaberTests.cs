using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Devices.Tests.Fakes;
using LaserEngrave.Devices.Zaber;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Devices.Tests.Integration;

/// <summary>The Zaber host over a real pty (SerialPortLink on both ends of a socat pair), in real time.</summary>
public sealed class SocatZaberTests : IAsyncDisposable
{
    private static readonly ZaberConnectionOptions Options = new() { CommandTimeout = TimeSpan.FromSeconds(1), BroadcastQuietPeriod = TimeSpan.FromMilliseconds(100) };

    private readonly SocatPair _pair = new();
    private readonly FakeZaberChain _devices;
    private readonly ZaberChain _chain;

    public SocatZaberTests()
    {
        _devices = new FakeZaberChain(SerialPortLink.Open(_pair.B), new FakeZaberDevice(1) { Firmware = 523 }, new FakeZaberDevice(2) { Firmware = 522 });
        _chain = ZaberChain.Open(_pair.A, MachineProfile.Default, TimeProvider.System, Options);
    }

    private static CancellationToken Token => TestContext.Current.CancellationToken;

    [Fact]
    public async Task DiscoverAsync_OverAPty_FindsBothAxes()
    {
        _devices[1].Mode = 0x80;

        var discovery = await _chain.DiscoverAsync(fixAutoReply: true, Token).Within();

        Assert.Equal([1, 2], discovery.Devices.Select(d => (int)d.DeviceNumber));
        Assert.Equal(523, discovery.Find(1)!.FirmwareVersion);
        Assert.True(discovery.Find(1)!.IsHomed);
        Assert.Equal(522, discovery.Find(2)!.FirmwareVersion);
        Assert.Empty(discovery.Notes);
    }

    [Fact]
    public async Task IdentifyAsync_OverAPty_ReadsTheDevice()
    {
        _devices[2].DeviceId = 6310;

        var identity = await _chain.Y.IdentifyAsync(Token).Within();

        Assert.Equal(new AxisIdentity(2, 6310, 522, 0, _devices[2].MaximumPosition), identity);
    }

    [Fact]
    public async Task MoveAbsoluteAsync_BothAxesTogether_EachArrives()
    {
        var moves = await Task.WhenAll(_chain.X.MoveAbsoluteAsync(302362, Token), _chain.Y.MoveAbsoluteAsync(100, Token)).Within();

        Assert.Equal([302362L, 100L], moves);
        Assert.Equal(302362, _devices[1].Position);
        Assert.Equal(100, _devices[2].Position);
        Assert.Equal(0, await _chain.X.HomeAsync(Token).Within());
    }

    [Fact]
    public async Task MoveAbsoluteAsync_BeyondTravel_ErrorNamesPortDeviceAndMeaning()
    {
        var error = await Assert.ThrowsAsync<ZaberException>(() => _chain.X.MoveAbsoluteAsync(700000, Token).Within());

        Assert.Equal($"{_pair.A}: device 1 (X) refused Move Absolute 700000: error 20, {ZaberErrorCodes.Describe(20)}", error.Message);
    }

    [Fact]
    public async Task GetPositionAsync_DeviceSilent_TimesOutNamingPortDeviceAndCommand()
    {
        _devices.Intercept = f => f.Command == ZaberCommand.ReturnCurrentPosition ? FakeZaberChain.Hold : null;

        var error = await Assert.ThrowsAsync<DeviceTimeoutException>(() => _chain.Y.GetPositionAsync(Token).Within());

        Assert.Equal($"{_pair.A}: device 2 (Y) did not reply to Return Current Position within 1000 ms", error.Message);
    }

    [Fact]
    public async Task MoveAbsoluteAsync_CableGoneMidMove_LinkLostNamesPortDeviceAndCommand()
    {
        await _chain.X.IdentifyAsync(Token).Within();
        _devices.Intercept = f => f.Command == ZaberCommand.MoveAbsolute ? FakeZaberChain.Hold : null;
        var move = _chain.X.MoveAbsoluteAsync(5000, Token);
        await _devices.NextAsync(ZaberCommand.MoveAbsolute);

        _pair.Kill();

        var error = await Assert.ThrowsAsync<LinkLostException>(() => move.Within());
        Assert.StartsWith($"{_pair.A}: the link was lost while waiting for device 1 (X) to reply to Move Absolute 5000", error.Message, StringComparison.Ordinal);
    }

    public async ValueTask DisposeAsync()
    {
        await _chain.DisposeAsync().AsTask().Within();
        await _devices.DisposeAsync().AsTask().Within();
        _pair.Dispose();
    }
}
