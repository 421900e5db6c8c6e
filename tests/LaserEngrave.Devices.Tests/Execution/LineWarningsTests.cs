using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Devices.Tests.Fakes;
using LaserEngrave.Devices.Zaber;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>Every unfinished frame the stage's line dropped during a run, for its log.</summary>
public class LineWarningsTests
{
    [Fact]
    public async Task Lines_PartialFrameDroppedAfterAGap_NamesItWithTheRunSecondsAndTheBytes()
    {
        using var clock = new VirtualTimeProvider();
        var (host, device) = InMemorySerialLink.CreatePair(ZaberRig.Port, clock);
        await using var chain = new ZaberChain(new ZaberConnection(host, clock), MachineProfile.Default);
        using var warnings = new LineWarnings(chain, clock);

        await clock.RunTestAsync(async () =>
        {
            await Task.Delay(TimeSpan.FromMilliseconds(1500), clock);
            await device.WriteAsync(new byte[] { 1, 60, 9 }, CancellationToken.None);
            await Task.Delay(TimeSpan.FromMilliseconds(12), clock);
            await device.WriteAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 5).ToBytes(), CancellationToken.None);
            await clock.SettleAsync();
        });

        var line = Assert.Single(warnings.Lines!);
        Assert.Equal($"1.512 s: {ZaberRig.Port}: dropped 3 byte(s) of an unfinished frame (013C09) after a gap of at least 12.0 ms", line);
    }

    [Fact]
    public async Task Lines_FrameInPiecesWithinTheTimeout_None()
    {
        using var clock = new VirtualTimeProvider();
        var (host, device) = InMemorySerialLink.CreatePair(ZaberRig.Port, clock);
        await using var chain = new ZaberChain(new ZaberConnection(host, clock), MachineProfile.Default);
        using var warnings = new LineWarnings(chain, clock);
        var bytes = new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 5).ToBytes();

        await clock.RunTestAsync(async () =>
        {
            await device.WriteAsync(bytes[..3], CancellationToken.None);
            await Task.Delay(TimeSpan.FromMilliseconds(3), clock);
            await device.WriteAsync(bytes[3..], CancellationToken.None);
            await clock.SettleAsync();
        });

        Assert.Null(warnings.Lines);
    }
}
