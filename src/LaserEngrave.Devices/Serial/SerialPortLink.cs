using System.Diagnostics;
using System.IO.Ports;
using System.Threading.Channels;
using LaserEngrave.Wire.Serial;
using Microsoft.Win32.SafeHandles;

namespace LaserEngrave.Devices.Serial;

/// <summary>A real serial port (or pty) as an <see cref="ISerialLink"/>, over System.IO.Ports.</summary>
/// <remarks>
/// <para>
/// One thread of its own per port reads <see cref="SerialPort.BaseStream"/> (never through DataReceived) with blocking
/// reads, stamps each read with the time it returned, and queues it; <see cref="ReadStampedAsync"/> hands that stamp on
/// as the latest the bytes can have arrived, with the earliest (<see cref="ArrivalProof"/>): a reader held up before it
/// read finds bytes that were waiting, and their read's stamp is late by its delay. The reader loop that awaits the queue continues on that thread too, so a reply is framed and
/// handed to its waiter as soon as the operating system returns it, even while the thread pool is busy (compiling,
/// running a job) or the machine is loaded (docs/zaber-protocol.md, Timeouts).
/// </para>
/// <para>
/// On Linux that thread and the writes use the port's file descriptor directly (<see cref="PosixPort"/>): System.IO.Ports'
/// own I/O loop wakes every millisecond while a read is pending, and on a loaded machine those wake-ups held other
/// processes' serial traffic (socat, the simulator) back by up to 1.3 s. The reader sleeps in poll() and looks every
/// 100 ms whether the port was closed; disposing wakes it at once and waits for it to end, so the port is closed (and no
/// longer read here) when disposal returns; on Windows closing the handle
/// aborts the pending read. A hang-up or unplug ends the pending read, so while the link is open that is reported as an
/// <see cref="IOException"/> naming the port, and later writes fail at once.
/// </para>
/// </remarks>
public sealed class SerialPortLink : ISerialLink
{
    private static readonly TimeSpan WriteTimeout = TimeSpan.FromSeconds(5);

    private readonly SerialPort _port;
    private readonly Stream _stream;
    private readonly SafeFileHandle? _lock;
    private readonly PosixPort? _posix;
    private readonly Lock _readerStart = new();
    private readonly Channel<Received> _received = Channel.CreateUnbounded<Received>(
        new UnboundedChannelOptions { SingleReader = true, AllowSynchronousContinuations = true });
    private Thread? _reader;
    private Received _pending = new([], 0, 0);
    private int _pendingOffset;
    private int _disposed;
    private volatile IOException? _failure;

    private SerialPortLink(SerialPortSettings settings, SerialPort port, SafeFileHandle? portLock)
    {
        Settings = settings;
        _port = port;
        _stream = port.BaseStream;
        _lock = portLock;
        _posix = PosixPort.TryOpen(_stream);
    }

    public SerialPortSettings Settings { get; }

    public string Name => Settings.PortName;

    public bool HasUnreadBytes
    {
        get
        {
            if (_received.Reader.TryPeek(out _) || Volatile.Read(ref _pendingOffset) < _pending.Data.Length)
            {
                return true;
            }

            try
            {
                return !IsDisposed && _failure is null && _port.BytesToRead > 0;
            }
            catch (Exception ex) when (ex is IOException or InvalidOperationException or ObjectDisposedException)
            {
                return false;
            }
        }
    }

    /// <summary>Opens and configures the port; throws a <see cref="SerialPortException"/> naming the port when it cannot.</summary>
    public static SerialPortLink Open(SerialPortSettings settings)
    {
        ArgumentNullException.ThrowIfNull(settings);
        settings.Validate();
        var name = settings.PortName;
        var portLock = OperatingSystem.IsWindows() ? null : LockUnixPort(name);
        var port = new SerialPort(name, settings.BaudRate, ToParity(settings.Parity), settings.DataBits, ToStopBits(settings.StopBits))
        {
            Handshake = ToHandshake(settings.Handshake),
            WriteTimeout = (int)WriteTimeout.TotalMilliseconds,
        };
        try
        {
            port.Open();
            RaiseModemLines(port);
            return new SerialPortLink(settings, port, portLock);
        }
        catch (Exception ex) when (ex is UnauthorizedAccessException or IOException or ArgumentException or InvalidOperationException)
        {
            port.Dispose();
            portLock?.Dispose();
            throw SerialPortErrors.FromOpenFailure(name, ex);
        }
    }

    /// <summary>Opens the port at 9600 8N1 without handshake.</summary>
    public static SerialPortLink Open(string portName, int baudRate = 9600) => Open(new SerialPortSettings(portName) { BaudRate = baudRate });

    public async ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken) =>
        (await ReadStampedAsync(buffer, TimeProvider.System, cancellationToken)).Count;

    public async ValueTask<StampedRead> ReadStampedAsync(Memory<byte> buffer, TimeProvider time, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(time);
        while (_pendingOffset >= _pending.Data.Length)
        {
            if (_failure is { } failure)
            {
                throw new IOException(failure.Message, failure);
            }

            if (IsDisposed)
            {
                return new StampedRead(0, time.GetTimestamp());
            }

            StartReader();
            bool more;
            try
            {
                more = await _received.Reader.WaitToReadAsync(cancellationToken);
            }
            catch (OperationCanceledException) when (IsDisposed)
            {
                more = false;
            }
            catch (IOException)
            {
                // The reader thread lost the port; _failure says how.
                more = false;
            }

            if (!more)
            {
                if (_failure is { } lost)
                {
                    throw new IOException(lost.Message, lost);
                }

                return new StampedRead(0, time.GetTimestamp());
            }

            if (_received.Reader.TryRead(out var received))
            {
                _pending = received;
                _pendingOffset = 0;
            }
        }

        var n = Math.Min(buffer.Length, _pending.Data.Length - _pendingOffset);
        _pending.Data.AsMemory(_pendingOffset, n).CopyTo(buffer);
        // Only the first piece of a read is bounded by what came before it; the rest of it arrived with it.
        var earliest = _pendingOffset == 0 ? _pending.Earliest : _pending.Stamp;
        _pendingOffset += n;
        return new StampedRead(n, StampedRead.OnClock(_pending.Stamp, TimeProvider.System, time))
        {
            EarliestArrival = StampedRead.OnClock(earliest, TimeProvider.System, time),
        };
    }

    public async ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken)
    {
        if (IsDisposed)
        {
            throw Closed(null);
        }

        if (_failure is { } failure)
        {
            throw new IOException(failure.Message, failure);
        }

        // The Linux stream applies WriteTimeout to synchronous writes only, so the asynchronous one gets its own deadline.
        using var deadline = CancellationTokenSource.CreateLinkedTokenSource(cancellationToken);
        deadline.CancelAfter(WriteTimeout);
        try
        {
            if (_posix is not null)
            {
                WritePosix(data.Span);
            }
            else
            {
                await _stream.WriteAsync(data, deadline.Token);
            }
        }
        catch (Exception ex) when (ex is OperationCanceledException or TimeoutException && !cancellationToken.IsCancellationRequested)
        {
            throw IsDisposed ? Closed(ex) : new IOException(
                $"{Name}: could not send within {WriteTimeout.TotalMilliseconds} ms (is handshake holding the line, or the port unplugged?)", ex);
        }
        catch (Exception ex) when (ex is ObjectDisposedException or IOException)
        {
            throw IsDisposed ? Closed(ex) : Lost(ex);
        }
    }

    /// <summary>Closes the port at once: a pending read returns 0, a pending write fails.</summary>
    public ValueTask DisposeAsync()
    {
        if (Interlocked.Exchange(ref _disposed, 1) != 0)
        {
            return ValueTask.CompletedTask;
        }

        // The stream first: SerialPort.Dispose flushes before closing, and that flush never returns once the device has
        // hung up with a write still queued. With the stream closed the port skips the flush.
        // The reader thread first, so that the port is really closed (and its bytes no longer read here) when this returns.
        if (_posix is not null)
        {
            _posix.Wake();
            Thread? reader;
            lock (_readerStart)
            {
                reader = _reader;
            }

            if (reader is not null && reader != Thread.CurrentThread)
            {
                reader.Join(TimeSpan.FromSeconds(1));
            }
        }

        _stream.Dispose();
        _received.Writer.TryComplete();
        _port.Dispose();
        _posix?.Dispose();
        _lock?.Dispose();
        return ValueTask.CompletedTask;
    }

    private bool IsDisposed => Volatile.Read(ref _disposed) != 0;

    private void StartReader()
    {
        lock (_readerStart)
        {
            if (_reader is not null)
            {
                return;
            }

            // Above normal where the system allows it (Windows); on Linux the thread of its own is what counts.
            _reader = new Thread(ReadLoop) { IsBackground = true, Name = $"serial reader {Name}", Priority = ThreadPriority.AboveNormal };
            _reader.Start();
        }
    }

    // Blocking reads on the port's own thread: each read is stamped when it returned, before anything else can delay it.
    private void ReadLoop()
    {
        var held = _posix?.TryHold() ?? false;
        if (_posix is not null && !held)
        {
            _received.Writer.TryComplete();
            return;
        }

        try
        {
            ReadUntilClosed();
        }
        finally
        {
            if (held)
            {
                _posix!.Release();
            }
        }
    }

    private void WritePosix(ReadOnlySpan<byte> data)
    {
        if (!_posix!.TryHold())
        {
            throw new ObjectDisposedException(Name);
        }

        try
        {
            _posix.Write(data, WriteTimeout);
        }
        finally
        {
            _posix.Release();
        }
    }

    private void ReadUntilClosed()
    {
        var buffer = new byte[512];
        var previous = long.MinValue;
        while (true)
        {
            int n;
            var quietAt = long.MinValue;
            try
            {
                n = _posix is not null ? _posix.Read(buffer, () => IsDisposed, out quietAt) : _stream.Read(buffer, 0, buffer.Length);
            }
            catch (Exception ex) when (IsDisposed && ex is ObjectDisposedException or IOException or OperationCanceledException or InvalidOperationException)
            {
                _received.Writer.TryComplete();
                return;
            }
            catch (Exception ex) when (ex is ObjectDisposedException or IOException or InvalidOperationException or OperationCanceledException)
            {
                _received.Writer.TryComplete(Lost(ex));
                return;
            }

            if (n == 0)
            {
                _received.Writer.TryComplete();
                return;
            }

            // Stamped when the read returned: the latest the bytes can have arrived. The earliest is the last time the port
            // was proven quiet (ArrivalProof); without such a proof (Windows' stream) no gap before them is proven.
            var stamp = Stopwatch.GetTimestamp();
            _received.Writer.TryWrite(new Received(buffer.AsSpan(0, n).ToArray(), stamp, ArrivalProof.Earliest(quietAt, previous, stamp)));
            previous = stamp;
        }
    }

    private IOException Closed(Exception? inner) => new($"{Name}: the port is closed", inner);

    private IOException Lost(Exception inner)
    {
        var lost = new IOException($"{Name}: the port was unplugged or its other end closed", inner);
        _failure ??= lost;
        return lost;
    }

    /// <summary>Takes an exclusive lock on the device itself (<see cref="PortLock"/>), so a second LaserEngrave (or a second open in this one) is refused.</summary>
    private static SafeFileHandle? LockUnixPort(string name)
    {
        string device;
        try
        {
            device = File.ResolveLinkTarget(name, returnFinalTarget: true) is { } target ? target.FullName : Path.GetFullPath(name);
        }
        catch (IOException)
        {
            throw SerialPortErrors.NoSuchPort(name);
        }

        // File.Exists is true for a dangling link (socat gone), so the link's final target is checked.
        if (!Path.Exists(device))
        {
            throw SerialPortErrors.NoSuchPort(name);
        }

        return PortLock.Take(device, name);
    }

    /// <summary>Raises DTR, and RTS unless the handshake drives it, as the native port did and terminal programs do.</summary>
    /// <remarks>System.IO.Ports lowers both at open, which leaves some adapters (and boards powered from DTR) silent.</remarks>
    private static void RaiseModemLines(SerialPort port)
    {
        try
        {
            port.DtrEnable = true;
            if (port.Handshake is Handshake.None or Handshake.XOnXOff)
            {
                port.RtsEnable = true;
            }
        }
        catch (IOException)
        {
            // A pty has no modem lines.
        }
    }

    private sealed record Received(byte[] Data, long Stamp, long Earliest);

    private static Parity ToParity(SerialParity parity) => parity switch
    {
        SerialParity.Odd => Parity.Odd,
        SerialParity.Even => Parity.Even,
        _ => Parity.None,
    };

    private static StopBits ToStopBits(SerialStopBits stopBits) => stopBits == SerialStopBits.Two ? StopBits.Two : StopBits.One;

    private static Handshake ToHandshake(SerialHandshake handshake) => handshake switch
    {
        SerialHandshake.RequestToSend => Handshake.RequestToSend,
        SerialHandshake.XOnXOff => Handshake.XOnXOff,
        _ => Handshake.None,
    };
}
