using System.Runtime.InteropServices;
using System.Runtime.Versioning;

namespace LaserEngrave.Devices.Serial.Unix;

/// <summary>A tty opened through libc: raw termios, exclusive, non-blocking, woken through a self-pipe.</summary>
[SupportedOSPlatform("linux")]
[SupportedOSPlatform("macos")]
internal sealed unsafe class UnixSerialPortBackend : SerialPortBackend
{
    private readonly string _name;
    private readonly UnixPlatform _os;
    private readonly int _fd;
    private readonly int _wakeRead;
    private readonly int _wakeWrite;
    private int _interrupted;
    private int _disposed;

    private UnixSerialPortBackend(string name, UnixPlatform os, int fd, int wakeRead, int wakeWrite)
    {
        _name = name;
        _os = os;
        _fd = fd;
        _wakeRead = wakeRead;
        _wakeWrite = wakeWrite;
    }

    public static UnixSerialPortBackend Open(SerialPortSettings settings)
    {
        var name = settings.PortName;
        var os = UnixPlatform.Current;
        var fd = LibC.Open(name, os.OpenFlags);
        if (fd < 0)
        {
            throw OpenError(name, Marshal.GetLastPInvokeError());
        }

        var wake = stackalloc int[2] { -1, -1 };
        try
        {
            // TIOCEXCL keeps other programs (except root) from opening the tty while we hold it; it fails with
            // ENOTTY when the path is not a terminal at all.
            if (LibC.Ioctl(fd, os.IoctlExclusive) != 0)
            {
                throw OpenError(name, Marshal.GetLastPInvokeError());
            }

            // TIOCEXCL does not stop root or a second LaserEngrave run by the same user; an advisory lock does.
            if (LibC.Flock(fd, UnixPlatform.LockExclusive | UnixPlatform.LockNonBlocking) != 0)
            {
                var errno = Marshal.GetLastPInvokeError();
                throw OpenError(name, errno == os.ErrAgain ? UnixPlatform.ErrBusy : errno);
            }

            Configure(fd, settings, os);
            LibC.TcFlush(fd, os.FlushBoth);

            if (LibC.Pipe(wake) != 0)
            {
                throw new SerialPortException(name, $"{name}: cannot open: {Marshal.GetPInvokeErrorMessage(Marshal.GetLastPInvokeError())}");
            }

            // pipe2 is Linux-only and fcntl is variadic, so close-on-exec is set with FIOCLEX.
            LibC.Ioctl(wake[0], os.IoctlCloseOnExec);
            LibC.Ioctl(wake[1], os.IoctlCloseOnExec);
            return new UnixSerialPortBackend(name, os, fd, wake[0], wake[1]);
        }
        catch
        {
            LibC.Close(fd);
            if (wake[0] >= 0)
            {
                LibC.Close(wake[0]);
                LibC.Close(wake[1]);
            }

            throw;
        }
    }

    private static SerialPortException OpenError(string name, int errno) => SerialPortErrors.FromErrno(name, errno);

    public override int Read(Span<byte> buffer)
    {
        var fds = stackalloc LibC.PollFd[2];
        while (true)
        {
            if (Volatile.Read(ref _interrupted) != 0)
            {
                return 0;
            }

            fds[0] = new LibC.PollFd { Fd = _fd, Events = UnixPlatform.PollIn };
            fds[1] = new LibC.PollFd { Fd = _wakeRead, Events = UnixPlatform.PollIn };
            if (LibC.Poll(fds, 2, -1) < 0)
            {
                var pollErrno = Marshal.GetLastPInvokeError();
                if (pollErrno == UnixPlatform.ErrInterrupted)
                {
                    continue;
                }

                throw Failure("wait for data", pollErrno);
            }

            if (fds[1].ReturnedEvents != 0)
            {
                return 0;
            }

            var events = fds[0].ReturnedEvents;
            if ((events & UnixPlatform.PollInvalid) != 0)
            {
                throw new IOException($"{_name}: the port was closed");
            }

            if (events == 0)
            {
                continue;
            }

            nint n;
            fixed (byte* p = buffer)
            {
                n = LibC.Read(_fd, p, (nuint)buffer.Length);
            }

            if (n > 0)
            {
                return (int)n;
            }

            if (n == 0)
            {
                throw new IOException($"{_name}: the other end hung up");
            }

            var errno = Marshal.GetLastPInvokeError();
            if (errno == UnixPlatform.ErrInterrupted || (errno == _os.ErrAgain && (events & UnixPlatform.PollIn) != 0))
            {
                continue;
            }

            if (errno == _os.ErrAgain)
            {
                throw new IOException($"{_name}: the other end hung up");
            }

            throw Failure("read", errno);
        }
    }

    public override void Write(ReadOnlySpan<byte> data)
    {
        var fds = stackalloc LibC.PollFd[2];
        fixed (byte* start = data)
        {
            var offset = 0;
            while (offset < data.Length)
            {
                if (Volatile.Read(ref _interrupted) != 0)
                {
                    throw new IOException($"{_name}: the port is closed");
                }

                var n = LibC.Write(_fd, start + offset, (nuint)(data.Length - offset));
                if (n > 0)
                {
                    offset += (int)n;
                    continue;
                }

                var errno = Marshal.GetLastPInvokeError();
                if (n < 0 && errno == UnixPlatform.ErrInterrupted)
                {
                    continue;
                }

                if (n < 0 && errno != _os.ErrAgain)
                {
                    throw Failure("write", errno);
                }

                // The transmit buffer is full (handshake held, or a slow line): wait until it drains or we are woken.
                fds[0] = new LibC.PollFd { Fd = _fd, Events = UnixPlatform.PollOut };
                fds[1] = new LibC.PollFd { Fd = _wakeRead, Events = UnixPlatform.PollIn };
                if (LibC.Poll(fds, 2, -1) < 0 && Marshal.GetLastPInvokeError() != UnixPlatform.ErrInterrupted)
                {
                    throw Failure("wait to write", Marshal.GetLastPInvokeError());
                }

                if ((fds[0].ReturnedEvents & (UnixPlatform.PollHangUp | UnixPlatform.PollErr | UnixPlatform.PollInvalid)) != 0)
                {
                    throw new IOException($"{_name}: the other end hung up");
                }
            }
        }
    }

    public override void Interrupt()
    {
        if (Interlocked.Exchange(ref _interrupted, 1) != 0)
        {
            return;
        }

        byte one = 1;
        LibC.Write(_wakeWrite, &one, 1);
    }

    public override void Dispose()
    {
        if (Interlocked.Exchange(ref _disposed, 1) != 0)
        {
            return;
        }

        LibC.Close(_fd);
        LibC.Close(_wakeRead);
        LibC.Close(_wakeWrite);
    }

    private static void Configure(int fd, SerialPortSettings settings, UnixPlatform os)
    {
        var name = settings.PortName;
        var termios = stackalloc byte[UnixPlatform.TermiosBufferSize];
        new Span<byte>(termios, UnixPlatform.TermiosBufferSize).Clear();
        if (LibC.TcGetAttr(fd, termios) != 0)
        {
            throw OpenError(name, Marshal.GetLastPInvokeError());
        }

        // Raw: no echo, no line editing, no character translation, no signals; 8 bits pass unchanged.
        LibC.CfMakeRaw(termios);

        var cflag = os.ReadCflag(termios);
        cflag &= ~(os.CSize | os.CStopB | os.ParEnb | os.ParOdd | os.CRtsCts);
        cflag |= os.CharacterSize(settings.DataBits) | os.CRead | os.CLocal;
        if (settings.StopBits == SerialStopBits.Two)
        {
            cflag |= os.CStopB;
        }

        cflag |= settings.Parity switch
        {
            SerialParity.Odd => os.ParEnb | os.ParOdd,
            SerialParity.Even => os.ParEnb,
            _ => 0,
        };
        if (settings.Handshake == SerialHandshake.RequestToSend)
        {
            cflag |= os.CRtsCts;
        }

        os.WriteCflag(termios, cflag);

        var iflag = os.ReadIflag(termios) & ~(os.IXon | os.IXoff);
        if (settings.Handshake == SerialHandshake.XOnXOff)
        {
            iflag |= os.IXon | os.IXoff;
        }

        os.WriteIflag(termios, iflag);

        if (!os.TrySetSpeed(termios, settings.BaudRate))
        {
            throw new SerialPortException(name, $"{name}: {settings.BaudRate} baud is not supported here (supported: {os.SupportedRates})");
        }

        if (LibC.TcSetAttr(fd, UnixPlatform.TcsaNow, termios) != 0)
        {
            var errno = Marshal.GetLastPInvokeError();
            throw new SerialPortException(name, $"{name}: cannot apply {settings}: {Marshal.GetPInvokeErrorMessage(errno)}");
        }
    }

    private IOException Failure(string what, int errno) =>
        errno == UnixPlatform.ErrIo
            ? new IOException($"{_name}: {what} failed: input/output error (the port was unplugged or its other end closed)")
            : new IOException($"{_name}: {what} failed: {Marshal.GetPInvokeErrorMessage(errno)}");
}
