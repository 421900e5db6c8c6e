using System.Diagnostics;
using System.Reflection;
using System.Runtime.InteropServices;

namespace LaserEngrave.Devices.Serial;

/// <summary>Blocking reads and writes on a Linux serial port's file descriptor, without System.IO.Ports' I/O loop.</summary>
/// <remarks>
/// On Linux, System.IO.Ports serves every pending read and write from a loop that wakes every millisecond. With a CPU
/// loaded by other work, those wake-ups delayed other processes' serial traffic by up to 1.3 s (measured: an unrelated
/// echo through socat, max 71-158 ms alone, 0.95-1.34 s beside an idle simulator with its two ports open), so replies
/// through socat timed out. Here the port's own reader thread sleeps in poll() until bytes arrive (waking every 100 ms
/// only to see whether the port was closed), and writes go straight to the descriptor. The descriptor is the one
/// System.IO.Ports opened and configured; it is held (a reference on its handle) until the reader thread ends, so it
/// cannot be closed and reused under it.
/// </remarks>
internal sealed class PosixPort : IDisposable
{
    private const short PollIn = 0x1;
    private const short PollOut = 0x4;
    private const short PollErr = 0x8;
    private const short PollHup = 0x10;
    private const short PollNval = 0x20;
    private const int EIntr = 4;
    private const int EAgain = 11;
    private const int DisposeCheckMs = 100;
    private const int EfdCloexec = 0x80000;
    private const int EfdNonblock = 0x800;

    private readonly SafeHandle _handle;
    private readonly int _fd;
    private readonly int _wake;
    private long _lastRead = long.MinValue;

    private PosixPort(SafeHandle handle, int wake)
    {
        _handle = handle;
        _fd = (int)handle.DangerousGetHandle();
        _wake = wake;
    }

    /// <summary>The descriptor under <paramref name="stream"/> on Linux; null elsewhere or when it cannot be found.</summary>
    public static PosixPort? TryOpen(Stream stream)
    {
        if (!OperatingSystem.IsLinux())
        {
            return null;
        }

        var field = stream.GetType().GetField("_handle", BindingFlags.NonPublic | BindingFlags.Instance);
        if (field?.GetValue(stream) is not SafeHandle { IsInvalid: false, IsClosed: false } handle)
        {
            return null;
        }

        // An eventfd that Wake signals, so that closing the port ends a pending poll() at once.
        var wake = NativeMethods.EventFd(0, EfdCloexec | EfdNonblock);
        return wake < 0 ? null : new PosixPort(handle, wake);
    }

    /// <summary>Ends a pending <see cref="Read"/> at once (it then asks whether the port was closed, and returns 0).</summary>
    public void Wake()
    {
        var one = BitConverter.GetBytes(1L);
        _ = NativeMethods.Write(_wake, one, (nuint)one.Length);
    }

    /// <summary>Keeps the descriptor open until <see cref="Release"/>, whoever disposes the stream meanwhile.</summary>
    public bool TryHold()
    {
        var held = false;
        try
        {
            _handle.DangerousAddRef(ref held);
        }
        catch (ObjectDisposedException)
        {
            return false;
        }

        return held;
    }

    public void Release() => _handle.DangerousRelease();

    /// <summary>Closes the wake-up descriptor, once the reader thread has ended.</summary>
    public void Dispose() => _ = NativeMethods.Close(_wake);

    /// <summary>Waits for bytes and reads them; 0 once <paramref name="closed"/> says the port was closed.</summary>
    /// <param name="buffer">Where the bytes go.</param>
    /// <param name="closed">Whether the port was closed meanwhile.</param>
    /// <param name="quietAt">
    /// The latest <see cref="Stopwatch"/> timestamp at which the port was proven to have nothing waiting, since the previous
    /// read (<see cref="long.MinValue"/>: none): the bytes returned arrived after it.
    /// </param>
    /// <exception cref="IOException">The other end hung up or the device failed.</exception>
    public int Read(byte[] buffer, Func<bool> closed, out long quietAt)
    {
        var fds = new[] { new PollFd { Fd = _fd, Events = PollIn }, new PollFd { Fd = _wake, Events = PollIn } };
        quietAt = long.MinValue;
        while (true)
        {
            if (closed())
            {
                return 0;
            }

            fds[0].Revents = 0;
            fds[1].Revents = 0;

            // Just after a read, short waits: each that times out proves the line quiet a little later, so a frame's real
            // gap is told from a reader that was merely late (ArrivalProof). Later, the usual long wait.
            var before = Stopwatch.GetTimestamp();
            var timeoutMs = ArrivalProof.PollTimeoutMs(_lastRead, before, DisposeCheckMs);
            var ready = NativeMethods.Poll(fds, 2, timeoutMs);
            if (closed())
            {
                // Never read once closed: the port may already be open again elsewhere, and its bytes are not ours.
                return 0;
            }

            if (ready < 0)
            {
                var errno = Marshal.GetLastPInvokeError();
                if (errno == EIntr)
                {
                    continue;
                }

                throw new IOException($"poll failed (errno {errno})");
            }

            if (ready == 0)
            {
                // The kernel looks at the port once more when the time is up: nothing was waiting then.
                quietAt = ArrivalProof.QuietAfterTimeout(quietAt, before, timeoutMs);
                continue;
            }

            if ((fds[0].Revents & PollIn) != 0)
            {
                var n = (int)NativeMethods.Read(_fd, buffer, (nuint)buffer.Length);
                if (n > 0)
                {
                    _lastRead = Stopwatch.GetTimestamp();
                    return n;
                }

                var errno = n < 0 ? Marshal.GetLastPInvokeError() : 0;
                if (n < 0 && errno is EIntr or EAgain)
                {
                    continue;
                }

                throw new IOException(n == 0 ? "end of stream" : $"read failed (errno {errno})");
            }

            if ((fds[0].Revents & (PollHup | PollErr | PollNval)) != 0)
            {
                throw new IOException("the port hung up");
            }
        }
    }

    /// <summary>Writes all of <paramref name="data"/> within <paramref name="timeout"/>.</summary>
    /// <exception cref="TimeoutException">The port took no more bytes for that long (handshake holding the line).</exception>
    /// <exception cref="IOException">The device failed.</exception>
    public void Write(ReadOnlySpan<byte> data, TimeSpan timeout)
    {
        var bytes = data.ToArray();
        var offset = 0;
        var deadline = Environment.TickCount64 + (long)timeout.TotalMilliseconds;
        var fds = new[] { new PollFd { Fd = _fd, Events = PollOut } };
        while (offset < bytes.Length)
        {
            var left = deadline - Environment.TickCount64;
            if (left <= 0)
            {
                throw new TimeoutException();
            }

            fds[0].Revents = 0;
            var ready = NativeMethods.Poll(fds, 1, (int)Math.Min(left, int.MaxValue));
            if (ready < 0 && Marshal.GetLastPInvokeError() != EIntr)
            {
                throw new IOException($"poll failed (errno {Marshal.GetLastPInvokeError()})");
            }

            if (ready <= 0)
            {
                continue;
            }

            if ((fds[0].Revents & (PollHup | PollErr | PollNval)) != 0 && (fds[0].Revents & PollOut) == 0)
            {
                throw new IOException("the port hung up");
            }

            var n = (int)NativeMethods.Write(_fd, bytes[offset..], (nuint)(bytes.Length - offset));
            if (n < 0)
            {
                var errno = Marshal.GetLastPInvokeError();
                if (errno is EIntr or EAgain)
                {
                    continue;
                }

                throw new IOException($"write failed (errno {errno})");
            }

            offset += n;
        }
    }

    [StructLayout(LayoutKind.Sequential)]
    private struct PollFd
    {
        public int Fd;
        public short Events;
        public short Revents;
    }

    private static class NativeMethods
    {
        [DllImport("libc", EntryPoint = "poll", SetLastError = true)]
        [DefaultDllImportSearchPaths(DllImportSearchPath.SafeDirectories)]
        public static extern int Poll([In, Out] PollFd[] fds, nuint count, int timeoutMs);

        [DllImport("libc", EntryPoint = "read", SetLastError = true)]
        [DefaultDllImportSearchPaths(DllImportSearchPath.SafeDirectories)]
        public static extern nint Read(int fd, [Out] byte[] buffer, nuint count);

        [DllImport("libc", EntryPoint = "eventfd", SetLastError = true)]
        [DefaultDllImportSearchPaths(DllImportSearchPath.SafeDirectories)]
        public static extern int EventFd(uint initial, int flags);

        [DllImport("libc", EntryPoint = "close", SetLastError = true)]
        [DefaultDllImportSearchPaths(DllImportSearchPath.SafeDirectories)]
        public static extern int Close(int fd);

        [DllImport("libc", EntryPoint = "write", SetLastError = true)]
        [DefaultDllImportSearchPaths(DllImportSearchPath.SafeDirectories)]
        public static extern nint Write(int fd, [In] byte[] buffer, nuint count);
    }
}
