using System.Threading.Channels;
using LaserEngrave.Devices.Serial.Unix;
using LaserEngrave.Devices.Serial.Windows;

namespace LaserEngrave.Devices.Serial;

/// <summary>A real serial port (or pty) as an <see cref="ISerialLink"/>, over the operating system's own API.</summary>
/// <remarks>
/// System.IO.Ports is not on this machine's package source, so the port is opened through P/Invoke: termios via libc
/// on Linux and macOS, the Win32 comm API on Windows. A dedicated thread blocks in the operating system's read and
/// hands the bytes to <see cref="ReadAsync"/>; disposing wakes that thread at once, so a pending read returns 0.
/// </remarks>
public sealed class NativeSerialPort : ISerialLink
{
    private static readonly TimeSpan ReaderExitWait = TimeSpan.FromSeconds(5);

    private readonly SerialPortBackend _backend;
    private readonly Channel<byte[]> _received = Channel.CreateUnbounded<byte[]>(new UnboundedChannelOptions { SingleReader = true, SingleWriter = true });
    private readonly TaskCompletionSource _readerDone = new(TaskCreationOptions.RunContinuationsAsynchronously);
    private readonly Lock _writeLock = new();
    private byte[] _pending = [];
    private int _pendingOffset;
    private int _disposed;
    private volatile IOException? _failure;

    private NativeSerialPort(SerialPortSettings settings, SerialPortBackend backend)
    {
        Settings = settings;
        _backend = backend;
        var reader = new Thread(ReaderLoop)
        {
            IsBackground = true,
            Name = $"serial reader {settings.PortName}",
        };
        reader.Start();
    }

    public SerialPortSettings Settings { get; }

    public string Name => Settings.PortName;

    /// <summary>Opens and configures the port; throws a <see cref="SerialPortException"/> naming the port when it cannot.</summary>
    public static NativeSerialPort Open(SerialPortSettings settings)
    {
        ArgumentNullException.ThrowIfNull(settings);
        settings.Validate();
        SerialPortBackend backend;
        if (OperatingSystem.IsWindows())
        {
            backend = WindowsSerialPortBackend.Open(settings);
        }
        else if (OperatingSystem.IsLinux() || OperatingSystem.IsMacOS())
        {
            backend = UnixSerialPortBackend.Open(settings);
        }
        else
        {
            throw new SerialPortException(settings.PortName, $"{settings.PortName}: serial ports are supported on Windows, Linux and macOS only");
        }

        return new NativeSerialPort(settings, backend);
    }

    /// <summary>Opens the port at 9600 8N1 without handshake.</summary>
    public static NativeSerialPort Open(string portName, int baudRate = 9600) => Open(new SerialPortSettings(portName) { BaudRate = baudRate });

    public async ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken)
    {
        while (_pendingOffset >= _pending.Length)
        {
            if (!await _received.Reader.WaitToReadAsync(cancellationToken).ConfigureAwait(false))
            {
                if (_failure is { } failure && Volatile.Read(ref _disposed) == 0)
                {
                    throw new IOException(failure.Message, failure);
                }

                return 0;
            }

            if (_received.Reader.TryRead(out var chunk))
            {
                _pending = chunk;
                _pendingOffset = 0;
            }
        }

        var n = Math.Min(buffer.Length, _pending.Length - _pendingOffset);
        _pending.AsMemory(_pendingOffset, n).CopyTo(buffer);
        _pendingOffset += n;
        return n;
    }

    public ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken)
    {
        cancellationToken.ThrowIfCancellationRequested();
        lock (_writeLock)
        {
            if (Volatile.Read(ref _disposed) != 0)
            {
                throw new IOException($"{Name}: the port is closed");
            }

            if (_failure is { } failure)
            {
                throw new IOException(failure.Message, failure);
            }

            // The operating system takes the bytes into its transmit buffer at once (a few bytes at 9600 baud), so a
            // synchronous write does not hold the caller for long.
            _backend.Write(data.Span);
        }

        return ValueTask.CompletedTask;
    }

    public async ValueTask DisposeAsync()
    {
        if (Interlocked.Exchange(ref _disposed, 1) != 0)
        {
            return;
        }

        _backend.Interrupt();
        _received.Writer.TryComplete();
        try
        {
            await _readerDone.Task.WaitAsync(ReaderExitWait).ConfigureAwait(false);
        }
        catch (TimeoutException)
        {
            // The reader thread is stuck in the driver; closing the handle below is what frees it.
        }

        lock (_writeLock)
        {
            _backend.Dispose();
        }
    }

    private void ReaderLoop()
    {
        var buffer = new byte[4096];
        try
        {
            while (true)
            {
                var n = _backend.Read(buffer);
                if (n == 0)
                {
                    break;
                }

                _received.Writer.TryWrite(buffer.AsSpan(0, n).ToArray());
            }
        }
        catch (IOException ex)
        {
            _failure = ex;
        }
        finally
        {
            _received.Writer.TryComplete();
            _readerDone.TrySetResult();
        }
    }
}
