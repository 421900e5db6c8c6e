using LaserEngrave.Wire.Serial;
using LaserEngrave.Wire.Zaber;
using Microsoft.Extensions.Time.Testing;

namespace LaserEngrave.Wire.Tests.Zaber;

/// <summary>Zaber framing on arrival times: the 10 ms inter-byte rule judges when bytes arrived, not when they were read.</summary>
public class ZaberFramerTests
{
    private static readonly TimeSpan PartialFrameTimeout = TimeSpan.FromMilliseconds(10);

    private readonly FakeTimeProvider _time = new();

    [Fact]
    public void Push_TwoPiecesArrived4MsApartReadTogether15MsLate_GivesTheFrame()
    {
        var dropped = new List<byte[]>();
        var framer = new ZaberFramer(PartialFrameTimeout, _time, dropped.Add);
        var frames = new List<ZaberFrame>();
        var bytes = new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 321).ToBytes();
        var start = _time.GetTimestamp();
        _time.Advance(TimeSpan.FromMilliseconds(15));

        framer.Push(bytes.AsSpan(0, 3), start, frames.Add);
        framer.Push(bytes.AsSpan(3), start + Ms(4), frames.Add);

        Assert.Equal([new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 321)], frames);
        Assert.Empty(dropped);
    }

    [Fact]
    public void Push_TwoPiecesArrived12MsApart_DropsTheUnfinishedFrame()
    {
        var dropped = new List<byte[]>();
        var framer = new ZaberFramer(PartialFrameTimeout, _time, dropped.Add);
        var frames = new List<ZaberFrame>();
        var bytes = new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 321).ToBytes();
        var start = _time.GetTimestamp();

        framer.Push(bytes.AsSpan(0, 3), start, frames.Add);
        framer.Push(bytes.AsSpan(3), start + Ms(12), frames.Add);
        framer.Push(bytes, start + Ms(30), frames.Add);

        Assert.Equal([new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 321)], frames);
        Assert.Equal([bytes[..3], bytes[3..]], dropped);
    }

    [Fact]
    public void Push_TwoPieces3MsApartOnTheWireRead30MsApartWithoutAQuietProof_KeepsTheFrame()
    {
        // A real port's reader stamps a read when it returned: piece two was already waiting when the late reader got to
        // it, 30 ms after piece one, and nothing proved the line quiet in between (the earliest it can have arrived is
        // piece one's read).
        var dropped = new List<byte[]>();
        var framer = new ZaberFramer(PartialFrameTimeout, _time, dropped.Add);
        var frames = new List<ZaberFrame>();
        var bytes = new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 321).ToBytes();
        var start = _time.GetTimestamp();

        framer.Push(bytes.AsSpan(0, 3), new StampedRead(3, start) { EarliestArrival = start - Ms(5) }, frames.Add);
        framer.Push(bytes.AsSpan(3), new StampedRead(3, start + Ms(30)) { EarliestArrival = start }, frames.Add);

        Assert.Equal([new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 321)], frames);
        Assert.Empty(dropped);
    }

    [Fact]
    public void Push_GapProvenByTheLineSeenQuiet12MsAfterThePiece_DropsTheUnfinishedFrame()
    {
        var dropped = new List<byte[]>();
        var framer = new ZaberFramer(PartialFrameTimeout, _time, dropped.Add);
        var frames = new List<ZaberFrame>();
        var bytes = new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 321).ToBytes();
        var start = _time.GetTimestamp();

        framer.Push(bytes.AsSpan(0, 3), new StampedRead(3, start) { EarliestArrival = start }, frames.Add);
        framer.Push(bytes, new StampedRead(6, start + Ms(14)) { EarliestArrival = start + Ms(12) }, frames.Add);

        Assert.Equal([new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 321)], frames);
        Assert.Equal([bytes[..3]], dropped);
        Assert.Equal(12, framer.LastDropGap.TotalMilliseconds, 6);
    }

    [Fact]
    public void Push_LineSeenQuietOnly8MsAfterThePieceThoughRead40MsLater_KeepsTheFrame()
    {
        var dropped = new List<byte[]>();
        var framer = new ZaberFramer(PartialFrameTimeout, _time, dropped.Add);
        var frames = new List<ZaberFrame>();
        var bytes = new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 321).ToBytes();
        var start = _time.GetTimestamp();

        framer.Push(bytes.AsSpan(0, 2), new StampedRead(2, start) { EarliestArrival = start }, frames.Add);
        framer.Push(bytes.AsSpan(2), new StampedRead(4, start + Ms(40)) { EarliestArrival = start + Ms(8) }, frames.Add);

        Assert.Equal([new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 321)], frames);
        Assert.Empty(dropped);
    }

    [Fact]
    public void Push_GarbageFrameDelivered_DiscardsTheRestOfTheBurstUntilTheLineIsQuiet()
    {
        var framer = new ZaberFramer(PartialFrameTimeout, _time);
        var frames = new List<ZaberFrame>();
        var burst = new ZaberFrame(9, ZaberCommand.ReturnCurrentPosition, 1).ToBytes().Concat(new ZaberFrame(1, ZaberCommand.Home, 0).ToBytes()).ToArray();
        var start = _time.GetTimestamp();

        framer.Push(burst, start, frame =>
        {
            frames.Add(frame);
            framer.DiscardUntilQuiet();
        });
        framer.Push(new byte[] { 1, 2 }, start + Ms(5), frames.Add);
        Assert.False(framer.ResetIfQuiet());
        _time.Advance(TimeSpan.FromMilliseconds(15));
        Assert.True(framer.ResetIfQuiet());
        framer.Push(new ZaberFrame(1, ZaberCommand.Home, 7).ToBytes(), _time.GetTimestamp(), frames.Add);

        Assert.Equal([new ZaberFrame(9, ZaberCommand.ReturnCurrentPosition, 1), new ZaberFrame(1, ZaberCommand.Home, 7)], frames);
    }

    private long Ms(int milliseconds) => (long)(milliseconds / 1000.0 * _time.TimestampFrequency);
}
