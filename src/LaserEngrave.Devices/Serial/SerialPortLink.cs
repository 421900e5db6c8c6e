using System.IO.Ports;
using Microsoft.Win32.SafeHandles;

namespace LaserEngrave.Devices.Serial;

/// <summary>A real serial port (or pty) as an <see cref="ISerialLink"/>, over System.IO.Ports.</summary>
/// <remarks>
/// Reads go straight to <see cref="SerialPort.BaseStream"/>, never through DataReceived. On Linux its I/O loop polls the
/// port every millisecond, so disposing the stream or cancelling the token ends a pending read at once (measured on a
/// pty: 1 ms, 25 ms the first time while the code is compiled); on Windows closing the handle aborts the pending read. A hang-up or unplug also ends the pending read with
/// "port is closed" and stops that I/O loop for good, so while the link is open that is reported as an
/// <see cref="IOException"/> naming the port, and later writes fail at once instead of waiting on a loop that is gone.
/// That millisecond poll costs about 4 % of one core per port while a read is pending (measured on this machine).
/// </remarks>
public sealed class SerialPortLink : ISerialLink
{
    private static readonly TimeSpan WriteTimeout = TimeSpan.FromSeconds(5);

    private readonly SerialPort _port;
    private readonly Stream _stream;
    private readonly SafeFileHandle? _lock;
    private int _disposed;
    private volatile IOException? _failure;

    private SerialPortLink(SerialPortSettings settings, SerialPort port, SafeFileHandle? portLock)
    {
        Settings = settings;
        _port = port;
        _stream = port.BaseStream;
        _lock = portLock;
    }

    public SerialPortSettings Settings { get; }

    public string Name => Settings.PortName;

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

    public async ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken)
    {
        if (_failure is { } failure)
        {
            throw new IOException(failure.Message, failure);
        }

        if (IsDisposed)
        {
            return 0;
        }

        try
        {
            return await _stream.ReadAsync(buffer, cancellationToken);
        }
        catch (Exception ex) when (IsDisposed && ex is ObjectDisposedException or IOException or OperationCanceledException)
        {
            return 0;
        }
        catch (Exception ex) when (ex is ObjectDisposedException or IOException)
        {
            throw Lost(ex);
        }
    }

    public async ValueTask<StampedRead> ReadStampedAsync(Memory<byte> buffer, TimeProvider time, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(time);
        var n = await ReadAsync(buffer, cancellationToken);
        return new StampedRead(n, time.GetTimestamp());
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
            await _stream.WriteAsync(data, deadline.Token);
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
        _stream.Dispose();
        _port.Dispose();
        _lock?.Dispose();
        return ValueTask.CompletedTask;
    }

    private bool IsDisposed => Volatile.Read(ref _disposed) != 0;

    private IOException Closed(Exception? inner) => new($"{Name}: the port is closed", inner);

    private IOException Lost(Exception inner)
    {
        var lost = new IOException($"{Name}: the port was unplugged or its other end closed", inner);
        _failure ??= lost;
        return lost;
    }

    /// <summary>Takes an exclusive lock for the port, so a second LaserEngrave (or a second open in this one) is refused.</summary>
    /// <remarks>
    /// System.IO.Ports sets TIOCEXCL, which keeps other users out but not root. The old native port also locked the tty
    /// itself with flock; .NET can only do that by opening the tty without O_NOCTTY, which makes it the controlling
    /// terminal of a session leader (a systemd service), and a hang-up would then kill the process. So the flock is
    /// taken on a small lock file named after the device instead; the files stay in the temp folder, since deleting a
    /// lock file that another process is about to lock would let both in.
    /// </remarks>
    private static SafeFileHandle LockUnixPort(string name)
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

        var lockPath = Path.Combine(Path.GetTempPath(), $"laserengrave-{device.Trim('/').Replace('/', '_')}.lock");
        try
        {
            return File.OpenHandle(lockPath, FileMode.OpenOrCreate, FileAccess.Read, FileShare.None);
        }
        catch (IOException)
        {
            throw SerialPortErrors.InUse(name);
        }
        catch (UnauthorizedAccessException)
        {
            throw new SerialPortException(name, $"{name}: cannot create the lock file {lockPath}");
        }
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
