using System.Threading.Channels;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Simulator.Serial;

/// <summary>One attachment of a simulated device to a link: bytes in and out, each taking its time on the wire.</summary>
/// <remarks>
/// <para>
/// Host to device: each write the host makes crosses its USB-serial adapter (the adapter's latency, drawn once per write),
/// then goes out at the baud rate, <c>bitsPerByte / baud</c> seconds a byte, behind whatever is still on the wire. A byte is
/// handed to the device when its last bit has arrived; the action a byte completes (a frame, a line) runs then, plus the
/// device's processing time.
/// </para>
/// <para>
/// Device to host: a reply leaves byte by byte behind the replies before it, and reaches the host when its last byte has
/// left plus the adapter's latency (drawn once per reply), never before an earlier reply; with <see cref="ReplyPieces"/>
/// some replies reach it in two pieces, the first early.
/// </para>
/// Reads never wait for virtual time, so every write is seen at the instant the host made it. A byte's arrival is when the
/// link says it arrived (on real ports, when the operating system returned it), not when this loop got to it: on a loaded
/// computer a frame read in two pieces late is not taken for a frame with a gap in it.
/// </remarks>
internal sealed class LinkSession
{
    private readonly ISerialLink _link;
    private readonly SimulationClock _clock;
    private readonly double _secondsPerByte;
    private readonly LinkLatency _latency;
    private readonly Action<string> _log;
    private readonly Channel<Delivery> _outgoing = Channel.CreateUnbounded<Delivery>(new() { SingleReader = true });
    private readonly Lock _sendLock = new();
    private readonly TimedSequence _actions;
    private readonly TimedSequence _deliveries;
    private string? _writeFailure;
    private readonly CancellationTokenSource _stop = new();
    private double _outBusyUntil;
    private double _lastDelivery;
    private double _inBusyUntil;
    private double _lastArrival = double.NegativeInfinity;
    private int _closed;
    private volatile bool _ended;

    public LinkSession(ISerialLink link, SimulationClock clock, int baudRate, int bitsPerByte, LinkLatency latency, Action<string> log)
    {
        _link = link;
        _clock = clock;
        _secondsPerByte = (double)bitsPerByte / baudRate;
        _latency = latency;
        _log = log;
        _actions = new TimedSequence(clock);
        _deliveries = new TimedSequence(clock);
    }

    public string Name => _link.Name;

    /// <summary>Queues <paramref name="data"/> to leave after whatever is already on the wire, <paramref name="extraDelay"/> late.</summary>
    public void Send(byte[] data, TimeSpan extraDelay = default)
    {
        lock (_sendLock)
        {
            var start = Math.Max(_clock.NowSeconds + extraDelay.TotalSeconds, _outBusyUntil);
            _outBusyUntil = start + (data.Length * _secondsPerByte);
            var previous = _lastDelivery;
            _lastDelivery = Math.Max(_outBusyUntil + _latency.ToHostSeconds(), _lastDelivery);
            if (_latency.Cut(data.Length) is { } cut)
            {
                // The adapter hands the first piece on early, never before its bytes have left the device nor before the
                // reply ahead of it; the last arrives when the whole reply would have.
                var first = Math.Max(Math.Max(_lastDelivery - cut.GapSeconds, start + (cut.At * _secondsPerByte)), previous);
                if (_clock.IsWallClock)
                {
                    // One delivery whose writer keeps the gap itself: two timed hand-overs on a loaded computer came
                    // 11-15 ms apart, a gap no adapter makes.
                    Deliver(new Delivery(data[..cut.At], first, data[cut.At..], _lastDelivery));
                }
                else
                {
                    Deliver(new Delivery(data[..cut.At], first));
                    Deliver(new Delivery(data[cut.At..], _lastDelivery));
                }
            }
            else
            {
                Deliver(new Delivery(data, _lastDelivery));
            }
        }
    }

    // Caller holds the send lock: deliveries are queued in their order.
    private void Deliver(Delivery delivery)
    {
        if (_clock.IsWallClock)
        {
            // Handed to the writer by the pacer at its instant, in order (deliveries never go back in time): the
            // system's timers would hand it a few milliseconds late. The write itself stays off the pacer's thread,
            // which every simulator of the process shares, since a port's write can block.
            _clock.At(delivery.AtSeconds, () => _outgoing.Writer.TryWrite(delivery));
        }
        else
        {
            _deliveries.Add(delivery.AtSeconds, () => Write(delivery.Data));
        }
    }

    /// <summary>Bytes to hand to the host at their time; on the wall clock a reply's last piece (<see cref="Tail"/>) rides with its first.</summary>
    private sealed record Delivery(byte[] Data, double AtSeconds, byte[]? Tail = null, double TailAtSeconds = 0);

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
    /// Serves the link until it closes: every received byte goes to <paramref name="onByte"/> with its arrival time; an
    /// action it returns runs at that time plus the device's processing time, in the order the bytes came.
    /// </summary>
    /// <param name="onByte">Takes each byte, its arrival time, and the gap since the previous byte's arrival (seconds).</param>
    /// <param name="cancellationToken">Ends the session.</param>
    public async Task RunAsync(Func<byte, double, double, Action?> onByte, CancellationToken cancellationToken)
    {
        using var linked = CancellationTokenSource.CreateLinkedTokenSource(cancellationToken, _stop.Token);
        var writer = _clock.IsWallClock ? WriteLoopAsync(linked.Token) : Task.FromResult<string?>(null);

        // What had not happened yet when the session ends never will (as the loops' delays were cancelled, at once).
        using var stopping = linked.Token.Register(() =>
        {
            _actions.Stop();
            _deliveries.Stop();
        });
        var why = "closed";
        try
        {
            why = await ReadLoopAsync(onByte, linked.Token);
        }
        finally
        {
            _ended = true;
            _outgoing.Writer.TryComplete();
            _actions.Stop();
            _deliveries.Stop();
            linked.Cancel();
            var writeFailure = await writer ?? _writeFailure;
            if (Volatile.Read(ref _closed) == 0 && !cancellationToken.IsCancellationRequested)
            {
                _log(writeFailure ?? why);
            }

            _stop.Dispose();
        }
    }

    private async Task<string> ReadLoopAsync(Func<byte, double, double, Action?> onByte, CancellationToken cancellationToken)
    {
        var buffer = new byte[256];
        var first = true;
        var lastAction = 0.0;
        while (true)
        {
            int n;
            double arrived;
            try
            {
                var read = await _link.ReadStampedAsync(buffer, _clock.Time, cancellationToken);
                n = read.Count;
                arrived = _clock.SecondsAt(read.ArrivalTimestamp);
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

            if (first)
            {
                first = false;
                _log("first bytes from the host");
            }

            // The adapter holds the whole write for its latency; then the bytes go out one after the other.
            var start = Math.Max(arrived + _latency.ToDeviceSeconds(), _inBusyUntil);
            for (var i = 0; i < n; i++)
            {
                _inBusyUntil = start + _secondsPerByte;
                start = _inBusyUntil;
                var gap = _inBusyUntil - _lastArrival;
                _lastArrival = _inBusyUntil;
                var action = onByte(buffer[i], _inBusyUntil, gap);
                if (action is null)
                {
                    continue;
                }

                // Actions keep their order even when a later one draws a shorter processing time.
                lastAction = Math.Max(_inBusyUntil + _latency.ProcessingSeconds(), lastAction);
                if (_clock.IsWallClock)
                {
                    // Run by the pacer at its instant, in order, as the write above.
                    _clock.At(lastAction, () =>
                    {
                        if (!_ended)
                        {
                            action();
                        }
                    });
                }
                else
                {
                    _actions.Add(lastAction, action);
                }
            }
        }
    }

    // In virtual time a delivery's bytes go onto the host's end at its instant, in order (_deliveries). The link in
    // process takes a write at once; once one failed, the link is given up and nothing more is written.
    private void Write(byte[] data)
    {
        if (_writeFailure is not null)
        {
            return;
        }

        try
        {
            var written = _link.WriteAsync(data, CancellationToken.None);
            if (!written.IsCompletedSuccessfully)
            {
                // Not a link this process serves in virtual time: the order of deliveries could not be kept.
                throw new InvalidOperationException($"{_link.Name}: a write in virtual time did not complete at once");
            }
        }
        catch (IOException ex)
        {
            _writeFailure = $"link failed: {ex.Message}";
            _deliveries.Stop();
            _ = _link.DisposeAsync().AsTask();
        }
    }

    // On the wall clock: the pacer hands each delivery over at its instant. Returns why writing failed, or null when it simply ended.
    private async Task<string?> WriteLoopAsync(CancellationToken cancellationToken)
    {
        try
        {
            // Not ReadAllAsync: it awaits with ConfigureAwait(false) inside, which would leave the simulation's loop.
            while (await _outgoing.Reader.WaitToReadAsync(cancellationToken))
            {
                while (_outgoing.Reader.TryRead(out var item))
                {
                    await _clock.DelayUntil(item.AtSeconds, cancellationToken);
                    await _link.WriteAsync(item.Data, cancellationToken);
                    if (item.Tail is { } tail)
                    {
                        // The gap measured from the first piece's write, spun (a few ms): a sleep would wake late.
                        var gap = item.TailAtSeconds - item.AtSeconds;
                        var written = System.Diagnostics.Stopwatch.GetTimestamp();
                        while (System.Diagnostics.Stopwatch.GetElapsedTime(written).TotalSeconds < gap)
                        {
                            Thread.SpinWait(20);
                        }

                        await _link.WriteAsync(tail, cancellationToken);
                    }
                }
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
            await _link.DisposeAsync();
            return why;
        }
    }
}
