using LaserEngrave.Simulator.Serial;

namespace LaserEngrave.Simulator.Tests.Serial;

public class StreamSerialLinkTests
{
    [Fact(Timeout = 10_000)]
    public async Task ReadAsync_StreamEnds_DeliversTheBytesThenZero()
    {
        var ct = TestContext.Current.CancellationToken;
        await using var link = new StreamSerialLink("test", new MemoryStream([1, 2, 3]));
        var buffer = new byte[8];

        var n = await link.ReadAsync(buffer, ct);

        Assert.Equal([1, 2, 3], buffer[..n]);
        Assert.Equal(0, await link.ReadAsync(buffer, ct));
    }

    [Fact(Timeout = 10_000)]
    public async Task ReadAsync_StreamFails_ThrowsIOExceptionNamingTheLink()
    {
        await using var link = new StreamSerialLink("/dev/ttyFAKE", new FailingStream());

        var ex = await Assert.ThrowsAsync<IOException>(async () => await link.ReadAsync(new byte[8], TestContext.Current.CancellationToken));

        Assert.Contains("/dev/ttyFAKE", ex.Message, StringComparison.Ordinal);
    }

    [Fact(Timeout = 10_000)]
    public async Task ReadAsync_Disposed_ReturnsZeroEvenWhileTheStreamBlocks()
    {
        var blocking = new BlockingStream();
        var link = new StreamSerialLink("test", blocking);
        var read = link.ReadAsync(new byte[8], TestContext.Current.CancellationToken).AsTask();

        await link.DisposeAsync();

        Assert.Equal(0, await read);
        blocking.Release();
    }

    [Fact(Timeout = 10_000)]
    public async Task WriteAsync_Disposed_ThrowsIOException()
    {
        var link = new StreamSerialLink("test", new MemoryStream());
        await link.DisposeAsync();

        await Assert.ThrowsAsync<IOException>(async () => await link.WriteAsync(new byte[] { 1 }, TestContext.Current.CancellationToken));
    }

    private sealed class FailingStream : MemoryStream
    {
        public override int Read(Span<byte> buffer) => throw new IOException("input/output error");
    }

    private sealed class BlockingStream : MemoryStream
    {
        private readonly ManualResetEventSlim _release = new();

        public void Release() => _release.Set();

        public override int Read(Span<byte> buffer)
        {
            _release.Wait(TimeSpan.FromSeconds(5));
            return 0;
        }
    }
}
