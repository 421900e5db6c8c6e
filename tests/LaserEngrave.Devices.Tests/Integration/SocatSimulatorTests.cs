using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.LaserGate;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Devices.Tests.Fakes;
using LaserEngrave.Devices.Zaber;
using LaserEngrave.Simulator;

namespace LaserEngrave.Devices.Tests.Integration;

/// <summary>
/// <see cref="ZaberChain.Open"/> and <see cref="PicLaserGate.Open"/> on one end of socat pty pairs, the simulator attached
/// to the other ends through <see cref="SerialPortLink"/>: the whole serial path as in the lab, without the lab.
/// </summary>
public sealed class SocatSimulatorTests : IAsyncDisposable
{
    private static readonly ZaberConnectionOptions Options = new() { CommandTimeout = TimeSpan.FromSeconds(1), BroadcastQuietPeriod = TimeSpan.FromMilliseconds(100) };
    private static readonly MachineProfile Profile = MachineProfile.Default with { Gate = new LaserGateProfile { TimeoutMs = 1000 } };

    private readonly SocatPair _stagePair = new();
    private readonly SocatPair _laserPair = new();
    private readonly SimulatedMachine _machine;
    private readonly ZaberChain _chain;
    private readonly PicLaserGate _gate;

    public SocatSimulatorTests()
    {
        _machine = SimulatedMachine.Attach(SerialPortLink.Open(_stagePair.B), SerialPortLink.Open(_laserPair.B), Profile);
        _chain = ZaberChain.Open(_stagePair.A, Profile, TimeProvider.System, Options);
        _gate = PicLaserGate.Open(_laserPair.A, Profile.Gate, TimeProvider.System);
    }

    private static CancellationToken Token => TestContext.Current.CancellationToken;

    [Fact]
    public async Task DiscoverAsync_SimulatedChain_FindsBothAxesWithTheirFirmware()
    {
        var discovery = await _chain.DiscoverAsync(fixAutoReply: false, Token).Within();

        Assert.Equal([Profile.X.DeviceNumber, Profile.Y.DeviceNumber], discovery.Devices.Select(d => (int)d.DeviceNumber));
        Assert.All(discovery.Devices, d => Assert.Equal(523, d.FirmwareVersion));
    }

    [Fact]
    public async Task MoveAbsoluteAsync_BothAxesTogether_SimulatedStageArrives()
    {
        // Short moves: a simulator on ports runs on the wall clock, at the stage's own (slow) power-up speed.
        var replies = await Task.WhenAll(_chain.X.MoveAbsoluteAsync(600_000, Token), _chain.Y.MoveAbsoluteAsync(601_234, Token)).Within();

        Assert.Equal([600_000L, 601_234L], replies);
        Assert.Equal(600_000, _machine.Stage.X.Position);
        Assert.Equal(601_234, _machine.Stage.Y.Position);
    }

    [Fact]
    public async Task MoveAbsoluteAsync_BeyondTravel_SimulatorRefusesAndNothingMoves()
    {
        var before = _machine.Stage.X.Position;

        var error = await Assert.ThrowsAsync<ZaberException>(() => _chain.X.MoveAbsoluteAsync(_machine.Stage.X.MaximumPosition + 1, Token).Within());

        Assert.StartsWith($"{_stagePair.A}: device 1 (X) refused Move Absolute", error.Message, StringComparison.Ordinal);
        Assert.Equal(before, _machine.Stage.X.Position);
    }

    [Fact]
    public async Task SetFrequencyAsync_ThenOff_SimulatedGateFiresAndStops()
    {
        Assert.Equal($"PICGATE {_machine.Options.GateFirmware}", await _gate.IdentifyAsync(Token).Within());

        await _gate.SetFrequencyAsync(1000, Token).Within();
        var firing = _machine.Gate.IsFiring;
        await _gate.OffAsync(Token).Within();

        Assert.True(firing);
        Assert.False(_machine.Gate.IsFiring);
        Assert.False((await _gate.GetStateAsync(Token).Within()).Firing);
    }

    [Fact]
    public async Task GetPositionAsync_SimulatorGoesSilent_TimesOutNamingPortDeviceAndCommand()
    {
        await _chain.Y.IdentifyAsync(Token).Within();
        _machine.Faults.Add("silent:stage");

        var error = await Assert.ThrowsAsync<DeviceTimeoutException>(() => _chain.Y.GetPositionAsync(Token).Within());

        Assert.Equal($"{_stagePair.A}: device 2 (Y) did not reply to Return Current Position within 1000 ms", error.Message);
    }

    public async ValueTask DisposeAsync()
    {
        await _chain.DisposeAsync().AsTask().Within();
        await _gate.DisposeAsync().AsTask().Within();
        await _machine.DisposeAsync().AsTask().Within();
        _stagePair.Dispose();
        _laserPair.Dispose();
    }
}
