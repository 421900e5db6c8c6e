using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Scheduling;
using LaserEngrave.Wire.Scheduling;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Devices.Serial;

/// <summary>The one owner of a serial link: its reader loop, its framing, its send lock, and how it closes.</summary>
/// <remarks>
/// <para>
/// One reader loop reads the link with arrival timestamps (when the bytes arrived, on the channel's clock, not when the
/// loop got to them), cuts them into messages with an <see cref="ISerialFramer{TMessage}"/> and hands each message to the
/// device that owns the channel (matching replies to requests stays with the device). Writes go
/// one at a time under <see cref="SendLock"/>, which a device may hold across a write and its reply.
/// </para>
/// <para>
/// The loop ends when the link reaches end of stream or fails (link lost) or when the channel is disposed (closed);
/// the device is told once, with the reason, and every later send fails with a <see cref="LinkLostException"/>.
/// The loop starts through <see cref="TaskRunner.For"/>, so it runs on the simulation's loop in the twin.
/// </para>
/// </remarks>
/// <typeparam name="TMessage">A Zaber frame, a line of text.</typeparam>
public sealed class SerialChannel<TMessage> : IAsyncDisposable
{
    private readonly ISerialLink _link;
    private readonly ISerialFramer<TMessage> _framer;
    private readonly Action<TMessage> _onMessage;
    private readonly Action<Exception?> _onClosed;
    private readonly Lock _sync = new();
    private readonly CancellationTokenSource _stop = new();
    private Task _readLoop = Task.CompletedTask;
    private long _bytesReceived;
    private long _lastWriteCompleted = long.MinValue;
    private volatile bool _dispatching;
    private bool _started;
    private bool _closed;
    private bool _disposing;
    private Exception? _closeReason;
    private int _disposed;

    /// <param name="link">The link; the channel disposes it.</param>
    /// <param name="framer">Cuts the bytes into messages.</param>
    /// <param name="time">The clock of the arrival stamps and of the loop's runner.</param>
    /// <param name="onMessage">Takes each message, on the reader loop: quick, and never waiting for a reply.</param>
    /// <param name="onClosed">Told once that the channel closed, with the link's failure (null: end of stream or disposal).</param>
    public SerialChannel(ISerialLink link, ISerialFramer<TMessage> framer, TimeProvider time, Action<TMessage> onMessage, Action<Exception?> onClosed)
    {
        ArgumentNullException.ThrowIfNull(link);
        ArgumentNullException.ThrowIfNull(framer);
        ArgumentNullException.ThrowIfNull(time);
        ArgumentNullException.ThrowIfNull(onMessage);
        ArgumentNullException.ThrowIfNull(onClosed);
        _link = link;
        _framer = framer;
        Time = time;
        _onMessage = onMessage;
        _onClosed = onClosed;
    }

    public string Name => _link.Name;

    public TimeProvider Time { get; }

    /// <summary>One writer at a time; held by a device across a write (and, where it must, its reply).</summary>
    public AsyncLock SendLock { get; } = new();

    /// <summary>Bytes taken from the link so far.</summary>
    public long BytesReceived => Interlocked.Read(ref _bytesReceived);

    /// <summary>True while bytes that have arrived are still on their way to the device: unread, or being framed and handed on.</summary>
    /// <remarks>A wait whose time is up asks it: a reply that arrived in time but was noticed late (a loaded machine) still answers.</remarks>
    public bool IsReceiving => _dispatching || _link.HasUnreadBytes;

    /// <summary>False once the link was lost or the channel disposed.</summary>
    public bool IsOpen
    {
        get
        {
            lock (_sync)
            {
                return !_closed;
            }
        }
    }

    /// <summary>"the connection was closed" once disposal began, else "the link was lost": for messages.</summary>
    public string ClosedState
    {
        get
        {
            lock (_sync)
            {
                return _disposing ? "the connection was closed" : "the link was lost";
            }
        }
    }

    /// <summary>Starts the reader loop; the owner calls it once it is ready for messages.</summary>
    public void Start()
    {
        lock (_sync)
        {
            if (_started)
            {
                throw new InvalidOperationException($"{Name}: the channel is already started");
            }

            _started = true;
            _readLoop = TaskRunner.For(Time).Start(ReadLoopAsync);
        }
    }

    /// <summary>
    /// When the bytes being framed now arrived (the read's arrival stamp, a timestamp of <see cref="Time"/>): valid inside
    /// the message callback, for the message the read completed. A round trip counted to it leaves out how late the reader
    /// and the waiter got to the reply (a busy computer), which is no latency of the link.
    /// </summary>
    public long CurrentArrival { get; private set; }

    /// <summary>When the latest write completed, as a timestamp of <see cref="Time"/>; null before the first.</summary>
    public long? LastWriteCompleted
    {
        get
        {
            var stamp = Interlocked.Read(ref _lastWriteCompleted);
            return stamp == long.MinValue ? null : stamp;
        }
    }

    /// <summary>Writes <paramref name="data"/>; a failing link becomes a <see cref="LinkLostException"/>.</summary>
    /// <param name="data">The bytes.</param>
    /// <param name="what">What is sent, as the start of the error ("/dev/ttyUSB0: cannot send Home to device 1").</param>
    /// <param name="cancellationToken">Cancels the write.</param>
    /// <returns>
    /// When the write completed (the link's write returned: on a real port, the operating system took the bytes), as a
    /// timestamp of <see cref="Time"/>. Not when it was asked for: a computer that stalls between the two (another process,
    /// a page fault) sends the bytes that much later, and only this stamp shows it.
    /// </returns>
    public async Task<long> WriteAsync(ReadOnlyMemory<byte> data, string what, CancellationToken cancellationToken)
    {
        try
        {
            await _link.WriteAsync(data, cancellationToken);
        }
        catch (Exception ex) when (ex is IOException or ObjectDisposedException or InvalidOperationException)
        {
            throw new LinkLostException($"{what}: {ex.Message}", ex);
        }

        var completed = Time.GetTimestamp();
        Interlocked.Exchange(ref _lastWriteCompleted, completed);
        return completed;
    }

    /// <summary>A <see cref="LinkLostException"/> with <paramref name="message"/> and the reason the link closed, if any.</summary>
    public LinkLostException LinkLost(string message)
    {
        Exception? reason;
        lock (_sync)
        {
            reason = _closeReason;
        }

        return reason is null ? new LinkLostException(message) : new LinkLostException($"{message} ({reason.Message})", reason);
    }

    /// <summary>Stops the reader loop and closes the link; the owner is told it closed.</summary>
    public async ValueTask DisposeAsync()
    {
        if (Interlocked.Exchange(ref _disposed, 1) != 0)
        {
            return;
        }

        lock (_sync)
        {
            _disposing = true;
        }

        _stop.Cancel();
        await _link.DisposeAsync();
        await _readLoop;
        Close(null);
        _stop.Dispose();
    }

    private async Task ReadLoopAsync()
    {
        var buffer = new byte[512];
        Exception? failure = null;
        try
        {
            while (true)
            {
                var read = await _link.ReadStampedAsync(buffer, Time, _stop.Token);
                if (read.Count == 0)
                {
                    break;
                }

                Interlocked.Add(ref _bytesReceived, read.Count);
                _dispatching = true;
                CurrentArrival = read.ArrivalTimestamp;
                try
                {
                    _framer.Push(buffer.AsSpan(0, read.Count), read, _onMessage);
                }
                finally
                {
                    _dispatching = false;
                }
            }
        }
        catch (OperationCanceledException) when (_stop.IsCancellationRequested)
        {
            // Disposal.
        }
#pragma warning disable CA1031 // Whatever ends the reader loop is handed to the owner as the reason the link was lost.
        catch (Exception ex)
#pragma warning restore CA1031
        {
            failure = ex;
        }

        Close(failure);
    }

    private void Close(Exception? reason)
    {
        lock (_sync)
        {
            if (_closed)
            {
                return;
            }

            _closed = true;
            _closeReason = reason;
        }

        _onClosed(reason);
    }
}
