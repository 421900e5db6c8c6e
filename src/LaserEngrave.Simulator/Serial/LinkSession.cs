using System.Threading.Channels;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Simulator.Timing;

namespace LaserEngrave.Simulator.Serial;

/// <summary>One attachment of a simulated device to a link: bytes in and out, each taking its time on the wire.</summary>
/// <remarks>
/// A byte occupies the wire for <c>bitsPerByte / baud</c> seconds in each direction: a received byte is handed on at
/// the moment its last bit arrives, and a reply is written to the link when its last byte would have left.
/// Replies leave in the order they were sent, one after the other.
/// </remarks>
internal sealed class LinkSession
{
    private readonly ISerialLink _link;
    private readonly SimulationClock _clock;
    private readonly double _secondsPerByte;
    private readonly Action<string> _log;
    private readonly Channel<(byte[] Data, double AtSeconds, ClockHold Hold)> _outgoing = Channel.CreateUnbounded<(byte[], double, ClockHold)>(new() { SingleReader = true });
    private readonly Lock _sendLock = new();
    private readonly CancellationTokenSource _stop = new();
    private double _outBusyUntil;
    private double _inBusyUntil;
    private double _hostBusyUntil;
    private double _hostLastArrival = double.NegativeInfinity;
    private int _closed;

    public LinkSession(ISerialLink link, SimulationClock clock, int baudRate, int bitsPerByte, Action<string> log)
    {
        _link = link;
        _clock = clock;
        _secondsPerByte = (double)bitsPerByte / baudRate;
        _log = log;
    }

    public string Name => _link.Name;

    /// <summary>Queues <paramref name="data"/> to leave after whatever is already on the wire, <paramref name="extraDelay"/> late.</summary>
    public void Send(byte[] data, TimeSpan extraDelay = default)
    {
        lock (_sendLock)
        {
            var start = Math.Max(_clock.NowSeconds + extraDelay.TotalSeconds, _outBusyUntil);
            _outBusyUntil = start + (data.Length * _secondsPerByte);
            // Held until the writer has set its timer, so the clock cannot pass the moment the bytes are due.
            var hold = _clock.Hold();
            if (!_outgoing.Writer.TryWrite((data, _outBusyUntil, hold)))
            {
                hold.Dispose();
            }
        }

        _clock.Signal();
    }

    /// <summary>Closes the link (a Disconnect fault); the session then ends.</summary>
    public void Close(string why)
    {
        if (Interlocked.Exchange(ref _closed, 1) == 0)
        {
            _log(why);
            _stop.Cancel();
            _ = _link.DisposeAsync().AsTask();
        }
    }

    /// <summary>
    /// Serves the link until it closes: every received byte goes to <paramref name="onByte"/> with its arrival time;
    /// an action it returns runs at that time, before later bytes are looked at.
    /// </summary>
    /// <param name="onByte">Takes each byte, its arrival time, and the gap since the previous byte on the host's clock (seconds).</param>
    /// <param name="starting">A hold on the clock taken when the session was started, released once the reader waits for bytes.</param>
    /// <param name="cancellationToken">Ends the session.</param>
    public async Task RunAsync(Func<byte, double, double, Action?> onByte, ClockHold starting, CancellationToken cancellationToken)
    {
        using var linked = CancellationTokenSource.CreateLinkedTokenSource(cancellationToken, _stop.Token);
        var writer = WriteLoopAsync(linked.Token);
        var why = "closed";
        try
        {
            why = await ReadLoopAsync(onByte, starting, linked.Token).ConfigureAwait(false);
        }
        finally
        {
            _outgoing.Writer.TryComplete();
            await linked.CancelAsync().ConfigureAwait(false);
            var writeFailure = await writer.ConfigureAwait(false);
            while (_outgoing.Reader.TryRead(out var unsent))
            {
                unsent.Hold.Dispose();
            }

            if (Volatile.Read(ref _closed) == 0 && !cancellationToken.IsCancellationRequested)
            {
                _log(writeFailure ?? why);
            }

            _stop.Dispose();
        }
    }

    private async Task<string> ReadLoopAsync(Func<byte, double, double, Action?> onByte, ClockHold starting, CancellationToken cancellationToken)
    {
        var buffer = new byte[256];
        var first = true;
        while (true)
        {
            int n;
            try
            {
                var read = _link.ReadAsync(buffer, cancellationToken);
                starting.Dispose();
                starting = default;
                n = await read.ConfigureAwait(false);
            }
            catch (OperationCanceledException)
            {
                return "stopped";
            }
            catch (IOException ex)
            {
                return $"link failed: {ex.Message}";
            }

            if (n == 0)
            {
                return "link closed by the other end";
            }

            _clock.Signal();
            var hold = _clock.Hold();
            try
            {
                if (first)
                {
                    first = false;
                    _log("first bytes from the host");
                }

                var receivedAt = _clock.NowSeconds;
                var hostReceivedAt = _clock.Host.NowSeconds;
                for (var i = 0; i < n; i++)
                {
                    // A byte cannot arrive before it was written, nor before the previous byte has finished arriving.
                    _inBusyUntil = Math.Max(receivedAt, _inBusyUntil) + _secondsPerByte;
                    _hostBusyUntil = Math.Max(hostReceivedAt, _hostBusyUntil) + _secondsPerByte;
                    var gap = _hostBusyUntil - _hostLastArrival;
                    _hostLastArrival = _hostBusyUntil;
                    var action = onByte(buffer[i], _inBusyUntil, gap);
                    if (action is null)
                    {
                        continue;
                    }

                    var arrival = _clock.DelayUntil(_inBusyUntil, cancellationToken);
                    hold.Dispose();
                    try
                    {
                        await arrival.ConfigureAwait(false);
                    }
                    catch (OperationCanceledException)
                    {
                        return "stopped";
                    }

                    hold = _clock.Hold();
                    action();
                }
            }
            finally
            {
                hold.Dispose();
            }
        }
    }

    // Returns why writing failed, or null when it simply ended.
    private async Task<string?> WriteLoopAsync(CancellationToken cancellationToken)
    {
        try
        {
            await foreach (var (data, at, hold) in _outgoing.Reader.ReadAllAsync(cancellationToken).ConfigureAwait(false))
            {
                var due = _clock.DelayUntil(at, cancellationToken);
                hold.Dispose();
                await due.ConfigureAwait(false);
                _clock.Signal();
                await _link.WriteAsync(data, cancellationToken).ConfigureAwait(false);
            }

            return null;
        }
        catch (OperationCanceledException)
        {
            return null;
        }
        catch (IOException ex)
        {
            var why = $"link failed: {ex.Message}";
            await _link.DisposeAsync().ConfigureAwait(false);
            return why;
        }
    }
}
