using System.Text;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Devices.Tests.Fakes;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Devices.Tests.Serial;

/// <summary>The channel that owns a link: reading with arrival times, framing, sending, closing and losing the link.</summary>
public class SerialChannelTests
{
    private static readonly CancellationToken None = CancellationToken.None;

    [Fact]
    public async Task ReadLoop_LinesInPieces_DeliversEachLineOnce()
    {
        using var clock = new VirtualTimeProvider();
        var (host, device) = InMemorySerialLink.CreatePair("/dev/fake", clock);
        var lines = new List<string>();
        var channel = new SerialChannel<string>(host, new LineFramer(), clock, lines.Add, _ => { });
        channel.Start();

        await clock.RunTestAsync(async () =>
        {
            await device.WriteAsync(Encoding.ASCII.GetBytes("OK PI"), None);
            await device.WriteAsync(Encoding.ASCII.GetBytes("CGATE\r\n\r\nOK FREQ 10\n"), None);
            await clock.SettleAsync();
            await channel.DisposeAsync();
        });

        Assert.Equal(["OK PICGATE", "OK FREQ 10"], lines);
        Assert.Equal(25, channel.BytesReceived);
    }

    [Fact]
    public async Task ReadStampedAsync_BytesReadLate_CarryTheTimeTheyWereWritten()
    {
        using var clock = new VirtualTimeProvider();
        var (host, device) = InMemorySerialLink.CreatePair("/dev/fake", clock);
        var buffer = new byte[16];

        await clock.RunTestAsync(async () =>
        {
            var written = clock.GetTimestamp();
            await device.WriteAsync(new byte[] { 1, 2, 3 }, None);
            await device.WriteArrivedAsync(new byte[] { 4 }, written + TimeSpan.FromMilliseconds(2).Ticks);
            await Task.Delay(TimeSpan.FromMilliseconds(20), clock);

            var first = await host.ReadStampedAsync(buffer, clock, None);
            var second = await host.ReadStampedAsync(buffer, clock, None);

            Assert.Equal(new StampedRead(3, written), first);
            Assert.Equal(new StampedRead(1, written + TimeSpan.FromMilliseconds(2).Ticks), second);
        });
    }

    [Fact]
    public async Task ReadLoop_LinkEnds_TellsTheOwnerOnceAndRefusesLaterSends()
    {
        using var clock = new VirtualTimeProvider();
        var (host, device) = InMemorySerialLink.CreatePair("/dev/fake", clock);
        var closed = 0;
        var channel = new SerialChannel<string>(host, new LineFramer(), clock, _ => { }, _ => closed++);
        channel.Start();

        await clock.RunTestAsync(async () =>
        {
            await device.DisposeAsync();
            await clock.SettleAsync();

            Assert.False(channel.IsOpen);
            Assert.Equal("the link was lost", channel.ClosedState);
            var error = await VirtualTime.ThrowsAsync<LinkLostException>(channel.WriteAsync(new byte[] { 1 }, "/dev/fake: cannot send PING", None));
            Assert.StartsWith("/dev/fake: cannot send PING: ", error.Message, StringComparison.Ordinal);
            await channel.DisposeAsync();
        });

        Assert.Equal(1, closed);
        Assert.Equal("the connection was closed", channel.ClosedState);
    }

    [Fact]
    public async Task LinkLost_LinkFailed_NamesTheFailureAsTheReason()
    {
        using var clock = new VirtualTimeProvider();
        var link = new FailingLink();
        Exception? reason = null;
        var channel = new SerialChannel<string>(link, new LineFramer(), clock, _ => { }, r => reason = r);
        channel.Start();

        await clock.RunTestAsync(async () =>
        {
            await clock.SettleAsync();
            var error = channel.LinkLost("/dev/fail: the link was lost while waiting for the reply to 'PING'");

            Assert.Same(link.Failure, reason);
            Assert.Equal("/dev/fail: the link was lost while waiting for the reply to 'PING' (/dev/fail: the port was unplugged)", error.Message);
            Assert.Same(link.Failure, error.InnerException);
            await channel.DisposeAsync();
        });
    }

    [Fact]
    public void Push_LongLine_IsCutAtTheMaximumLength()
    {
        var framer = new LineFramer(maxLength: 4);
        var lines = new List<string>();

        framer.Push("ABCDEFG\nHI\r"u8, 0, lines.Add);

        Assert.Equal(["ABCD", "HI"], lines);
    }

    private sealed class FailingLink : ISerialLink
    {
        public IOException Failure { get; } = new("/dev/fail: the port was unplugged");

        public string Name => "/dev/fail";

        public bool HasUnreadBytes => false;

        public ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken) => ValueTask.FromException<int>(Failure);

        public ValueTask<StampedRead> ReadStampedAsync(Memory<byte> buffer, TimeProvider time, CancellationToken cancellationToken) =>
            ValueTask.FromException<StampedRead>(Failure);

        public ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken) => ValueTask.FromException(Failure);

        public ValueTask DisposeAsync() => ValueTask.CompletedTask;
    }
}
