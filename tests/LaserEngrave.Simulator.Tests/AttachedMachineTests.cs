using System.Text;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Simulator.Tests;

/// <summary>An attached machine in virtual time: the devices fast-forward, but what measures the host (another process) runs on the wall clock.</summary>
public class AttachedMachineTests
{
    [Fact(Timeout = 20_000)]
    public async Task Attach_HostSilentForTheWatchdogTime_LaserGoesOff()
    {
        var ct = TestContext.Current.CancellationToken;
        var (_, stageDevice) = InMemorySerialLink.CreatePair();
        var (laserHost, laserDevice) = InMemorySerialLink.CreatePair();
        await using var machine = SimulatedMachine.Attach(stageDevice, laserDevice, MachineProfile.Default);

        await laserHost.WriteAsync(Encoding.ASCII.GetBytes("WDOG 100\n"), ct);
        await ReadAsync(laserHost, "OK WDOG 100\n".Length, ct);
        await laserHost.WriteAsync(Encoding.ASCII.GetBytes("FREQ 1000\n"), ct);
        await ReadAsync(laserHost, "OK FREQ 1000\n".Length, ct);
        while (machine.Gate.IsFiring)
        {
            await Task.Delay(20, ct);
        }

        Assert.Equal(1, machine.Gate.WatchdogTrips);
    }

    [Fact(Timeout = 20_000)]
    public async Task Attach_PartialFrameThenAWallClockPause_IsDiscarded()
    {
        var ct = TestContext.Current.CancellationToken;
        var (stageHost, stageDevice) = InMemorySerialLink.CreatePair();
        var (_, laserDevice) = InMemorySerialLink.CreatePair();
        await using var machine = SimulatedMachine.Attach(stageDevice, laserDevice, MachineProfile.Default);

        // No timer is pending, so virtual time does not move during the pause: the gap must be measured on the wall clock.
        await stageHost.WriteAsync(new byte[] { 1, 55, 9 }, ct);
        await Task.Delay(100, ct);
        await stageHost.WriteAsync(new ZaberFrame(2, ZaberCommand.EchoData, 77).ToBytes(), ct);

        Assert.Equal(new ZaberFrame(2, ZaberCommand.EchoData, 77), ZaberFrame.Decode(await ReadAsync(stageHost, 6, ct)));
    }

    private static async Task<byte[]> ReadAsync(ISerialLink link, int count, CancellationToken ct)
    {
        var buffer = new byte[count];
        var read = 0;
        while (read < count)
        {
            var n = await link.ReadAsync(buffer.AsMemory(read), ct).AsTask().WaitAsync(TimeSpan.FromSeconds(10), ct);
            Assert.True(n > 0, "the link closed");
            read += n;
        }

        return buffer;
    }
}
