using System.Text;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Serial;

using LaserEngrave.Testing;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Simulator.Tests.Serial;

/// <summary>The simulator attached to real ptys (socat) through <see cref="SerialPortLink"/>, spoken to with raw bytes through the other ends.</summary>
public class PtyAttachTests
{
    private static readonly TimeSpan WallTimeout = TimeSpan.FromSeconds(10);

    [Fact(Timeout = 30_000)]
    public async Task Attach_SocatPtys_StageAndGateAnswerRawBytes()
    {
        var ct = TestContext.Current.CancellationToken;
        await using var stagePair = await SocatPtyPair.StartAsync(ct);
        await using var laserPair = await SocatPtyPair.StartAsync(ct);
        await using var machine = SimulatedMachine.Attach(
            SerialPortLink.Open(stagePair.A),
            SerialPortLink.Open(laserPair.A),
            MachineProfile.Default);
        await using var stage = SocatPtyPair.Open(stagePair.B);
        await using var laser = SocatPtyPair.Open(laserPair.B);

        await stage.WriteAsync(new ZaberFrame(0, ZaberCommand.ReturnFirmwareVersion, 0).ToBytes(), ct);
        var first = ZaberFrame.Decode(await ReadExactlyAsync(stage, 6, ct));
        var second = ZaberFrame.Decode(await ReadExactlyAsync(stage, 6, ct));
        await stage.WriteAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 600_000).ToBytes(), ct);
        var move = ZaberFrame.Decode(await ReadExactlyAsync(stage, 6, ct));
        await laser.WriteAsync(Encoding.ASCII.GetBytes("FREQ 1000\n"), ct);
        var ack = Encoding.ASCII.GetString(await ReadExactlyAsync(laser, "OK FREQ 1000\n".Length, ct));

        Assert.Equal(new ZaberFrame(1, ZaberCommand.ReturnFirmwareVersion, 523), first);
        Assert.Equal(new ZaberFrame(2, ZaberCommand.ReturnFirmwareVersion, 523), second);
        // A short move: on ports the simulator runs on the wall clock.
        Assert.Equal(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 600_000), move);
        Assert.Equal("OK FREQ 1000\n", ack);
        Assert.True(machine.Gate.IsFiring);
    }

    [Fact(Timeout = 30_000)]
    public async Task Attach_FramesForBothAxesInOneWrite_BothAnswer()
    {
        var ct = TestContext.Current.CancellationToken;
        await using var stagePair = await SocatPtyPair.StartAsync(ct);
        await using var laserPair = await SocatPtyPair.StartAsync(ct);
        await using var machine = SimulatedMachine.Attach(
            SerialPortLink.Open(stagePair.A),
            SerialPortLink.Open(laserPair.A),
            MachineProfile.Default);
        await using var stage = SocatPtyPair.Open(stagePair.B);

        for (var round = 0; round < 20; round++)
        {
            var both = new ZaberFrame(1, ZaberCommand.ReturnSetting, (int)ZaberCommand.SetTargetSpeed).ToBytes()
                .Concat(new ZaberFrame(2, ZaberCommand.ReturnSetting, (int)ZaberCommand.SetTargetSpeed).ToBytes()).ToArray();
            await stage.WriteAsync(both, ct);
            var replies = await ReadExactlyAsync(stage, 12, ct);

            Assert.Equal(new byte[] { 1, 2 }, new[] { replies[0], replies[6] }.Order().ToArray());
        }
    }

    // A pty file's reads block: read on a thread of its own rather than tie up the thread pool.
    private static async Task<byte[]> ReadExactlyAsync(Stream stream, int count, CancellationToken ct)
    {
        var buffer = new byte[count];
        await Task.Factory.StartNew(() => stream.ReadExactly(buffer), ct, TaskCreationOptions.LongRunning, TaskScheduler.Default).WaitAsync(WallTimeout, ct);
        return buffer;
    }
}
