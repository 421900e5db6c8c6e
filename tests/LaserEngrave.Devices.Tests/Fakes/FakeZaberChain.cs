using System.Threading.Channels;
using LaserEngrave.Devices.Scheduling;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Scheduling;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Devices.Tests.Fakes;

/// <summary>Fake Zaber devices on the device end of a link: records every frame, answers through
/// <see cref="FakeZaberDevice"/> unless <see cref="Intercept"/> says otherwise, and lets the test send any bytes.</summary>
/// <remarks>Given a <see cref="VirtualTimeProvider"/>, it runs on that clock's loop (so a test sees every reply in
/// virtual-time order, with no wall-clock waits); otherwise on the thread pool (real ports), guarded by <see cref="Eventually.Limit"/>.</remarks>
public sealed class FakeZaberChain : IAsyncDisposable
{
    private readonly ISerialLink _link;
    private readonly Channel<ZaberFrame> _received = Channel.CreateUnbounded<ZaberFrame>();
    private readonly AsyncLock _writeLock = new();
    private readonly CancellationTokenSource _stop = new();
    private readonly Task _loop;
    private readonly bool _onLoop;
    private int _disposed;

    public FakeZaberChain(ISerialLink deviceEnd, params FakeZaberDevice[] devices)
        : this(deviceEnd, null, devices)
    {
    }

    public FakeZaberChain(ISerialLink deviceEnd, TimeProvider? time, params FakeZaberDevice[] devices)
    {
        _link = deviceEnd;
        Devices = devices;
        _onLoop = time is VirtualTimeProvider;
        _loop = TaskRunner.For(time ?? TimeProvider.System).Start(LoopAsync);
    }

    public IReadOnlyList<FakeZaberDevice> Devices { get; }

    /// <summary>Decides the answer to a frame: null lets the devices answer; <see cref="Hold"/> answers nothing.</summary>
    public Func<ZaberFrame, IReadOnlyList<ZaberFrame>?>? Intercept { get; set; }

    /// <summary>Every frame received, in order.</summary>
    public List<ZaberFrame> Log { get; } = [];

    public static IReadOnlyList<ZaberFrame> Hold { get; } = [];

    public FakeZaberDevice this[byte number] => Devices.Single(d => d.Number == number);

    /// <summary>Waits for the next frame from the host.</summary>
    public async Task<ZaberFrame> NextAsync() => _onLoop ? await _received.Reader.ReadAsync() : await _received.Reader.ReadAsync().AsTask().Within();

    /// <summary>Waits for the next frame with this command, skipping others.</summary>
    public async Task<ZaberFrame> NextAsync(ZaberCommand command)
    {
        while (true)
        {
            var frame = await NextAsync();
            if (frame.Command == command)
            {
                return frame;
            }
        }
    }

    public Task SendAsync(params ZaberFrame[] frames) => SendRawAsync(frames.SelectMany(f => f.ToBytes()).ToArray());

    public async Task SendRawAsync(byte[] bytes)
    {
        await _writeLock.WaitAsync();
        try
        {
            await _link.WriteAsync(bytes, CancellationToken.None);
        }
        finally
        {
            _writeLock.Release();
        }
    }

    public async ValueTask DisposeAsync()
    {
        if (Interlocked.Exchange(ref _disposed, 1) != 0)
        {
            return;
        }

        _stop.Cancel();
        await _link.DisposeAsync();
        try
        {
            await (_onLoop ? _loop : _loop.Within());
        }
        catch (OperationCanceledException)
        {
        }

        _stop.Dispose();
    }

    private async Task LoopAsync()
    {
        var frame = new byte[ZaberFrame.Length];
        var count = 0;
        var buffer = new byte[256];
        while (true)
        {
            int n;
            try
            {
                n = await _link.ReadAsync(buffer, _stop.Token);
            }
            catch (Exception ex) when (ex is OperationCanceledException or IOException)
            {
                return;
            }

            if (n == 0)
            {
                return;
            }

            for (var i = 0; i < n; i++)
            {
                frame[count++] = buffer[i];
                if (count == ZaberFrame.Length)
                {
                    count = 0;
                    await OnFrameAsync(ZaberFrame.Decode(frame));
                }
            }
        }
    }

    private async Task OnFrameAsync(ZaberFrame frame)
    {
        lock (Log)
        {
            Log.Add(frame);
        }

        var replies = Intercept?.Invoke(frame)
            ?? Devices.Where(d => frame.Device == 0 || frame.Device == d.Number).SelectMany(d => d.Handle(frame)).ToArray();
        _received.Writer.TryWrite(frame);
        if (replies.Count > 0)
        {
            try
            {
                await SendAsync([.. replies]);
            }
            catch (IOException)
            {
                // The host end is gone.
            }
        }
    }
}
