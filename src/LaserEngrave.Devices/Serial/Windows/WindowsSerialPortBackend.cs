using System.Runtime.InteropServices;
using System.Runtime.Versioning;
using Microsoft.Win32.SafeHandles;

namespace LaserEngrave.Devices.Serial.Windows;

/// <summary>A COM port opened through kernel32 with overlapped I/O, so a blocked read never holds up a write.</summary>
/// <remarks>
/// A synchronous handle would serialise ReadFile and WriteFile on the same port, so the handle is overlapped and each
/// call waits for its own completion. Reads return as soon as one byte is there, or after
/// <see cref="ReadPollMs"/> with nothing, so the loop notices an interrupt even if CancelIoEx missed the read.
/// </remarks>
[SupportedOSPlatform("windows")]
internal sealed unsafe class WindowsSerialPortBackend : SerialPortBackend
{
    private const uint ReadPollMs = 200;
    private const uint WriteTimeoutMs = 5000;
    private const int ReadBufferSize = 4096;

    private readonly string _name;
    private readonly SafeFileHandle _handle;
    private readonly ManualResetEvent _readEvent = new(false);
    private readonly ManualResetEvent _writeEvent = new(false);
    private readonly NativeOverlapped* _readOverlapped;
    private readonly NativeOverlapped* _writeOverlapped;
    private readonly byte* _readBuffer;
    private int _interrupted;
    private int _disposed;

    private WindowsSerialPortBackend(string name, SafeFileHandle handle)
    {
        _name = name;
        _handle = handle;
        _readOverlapped = (NativeOverlapped*)NativeMemory.AllocZeroed((nuint)sizeof(NativeOverlapped));
        _writeOverlapped = (NativeOverlapped*)NativeMemory.AllocZeroed((nuint)sizeof(NativeOverlapped));
        _readBuffer = (byte*)NativeMemory.Alloc(ReadBufferSize);
    }

    public static WindowsSerialPortBackend Open(SerialPortSettings settings)
    {
        var name = settings.PortName;

        // COM10 and above are only reachable through the device namespace; the prefix works for COM1..COM9 too.
        var path = name.StartsWith(@"\\.\", StringComparison.Ordinal) ? name : @"\\.\" + name;
        var handle = Kernel32.CreateFile(path, Kernel32.GenericRead | Kernel32.GenericWrite, 0, 0, Kernel32.OpenExisting, Kernel32.FileFlagOverlapped, 0);
        if (handle.IsInvalid)
        {
            var error = Marshal.GetLastPInvokeError();
            handle.Dispose();
            throw SerialPortErrors.FromWin32(name, error);
        }

        try
        {
            if (Kernel32.GetFileType(handle) != Kernel32.FileTypeChar)
            {
                throw SerialPortErrors.NotASerialPort(name);
            }

            Configure(handle, settings);
            return new WindowsSerialPortBackend(name, handle);
        }
        catch
        {
            handle.Dispose();
            throw;
        }
    }

    public override int Read(Span<byte> buffer)
    {
        while (true)
        {
            if (Volatile.Read(ref _interrupted) != 0)
            {
                return 0;
            }

            _readEvent.Reset();
            *_readOverlapped = default;
            _readOverlapped->EventHandle = _readEvent.SafeWaitHandle.DangerousGetHandle();
            var count = (uint)Math.Min(buffer.Length, ReadBufferSize);
            if (!Kernel32.ReadFile(_handle, _readBuffer, count, null, _readOverlapped))
            {
                var error = Marshal.GetLastPInvokeError();
                if (error != Kernel32.ErrorIoPending)
                {
                    throw Failure("read", error);
                }
            }

            uint transferred;
            if (!Kernel32.GetOverlappedResult(_handle, _readOverlapped, &transferred, true))
            {
                var error = Marshal.GetLastPInvokeError();
                if (error == Kernel32.ErrorOperationAborted)
                {
                    continue;
                }

                throw Failure("read", error);
            }

            if (transferred > 0)
            {
                new ReadOnlySpan<byte>(_readBuffer, (int)transferred).CopyTo(buffer);
                return (int)transferred;
            }
        }
    }

    public override void Write(ReadOnlySpan<byte> data)
    {
        fixed (byte* start = data)
        {
            var offset = 0;
            while (offset < data.Length)
            {
                if (Volatile.Read(ref _interrupted) != 0)
                {
                    throw new IOException($"{_name}: the port is closed");
                }

                _writeEvent.Reset();
                *_writeOverlapped = default;
                _writeOverlapped->EventHandle = _writeEvent.SafeWaitHandle.DangerousGetHandle();
                if (!Kernel32.WriteFile(_handle, start + offset, (uint)(data.Length - offset), null, _writeOverlapped))
                {
                    var error = Marshal.GetLastPInvokeError();
                    if (error != Kernel32.ErrorIoPending)
                    {
                        throw Failure("write", error);
                    }
                }

                uint transferred;
                if (!Kernel32.GetOverlappedResult(_handle, _writeOverlapped, &transferred, true))
                {
                    throw Failure("write", Marshal.GetLastPInvokeError());
                }

                if (transferred == 0)
                {
                    throw new IOException($"{_name}: write timed out after {WriteTimeoutMs} ms (is handshake holding the line?)");
                }

                offset += (int)transferred;
            }
        }
    }

    public override void Interrupt()
    {
        if (Interlocked.Exchange(ref _interrupted, 1) == 0)
        {
            // Cancels the pending read and write of every thread on this handle.
            Kernel32.CancelIoEx(_handle, null);
        }
    }

    public override void Dispose()
    {
        if (Interlocked.Exchange(ref _disposed, 1) != 0)
        {
            return;
        }

        _handle.Dispose();
        NativeMemory.Free(_readOverlapped);
        NativeMemory.Free(_writeOverlapped);
        NativeMemory.Free(_readBuffer);
        _readEvent.Dispose();
        _writeEvent.Dispose();
    }

    private static void Configure(SafeFileHandle handle, SerialPortSettings settings)
    {
        var name = settings.PortName;
        var dcb = new Kernel32.Dcb { DcbLength = (uint)sizeof(Kernel32.Dcb) };
        if (!Kernel32.GetCommState(handle, &dcb))
        {
            throw new SerialPortException(name, $"{name}: not a serial port ({Marshal.GetPInvokeErrorMessage(Marshal.GetLastPInvokeError())})");
        }

        dcb.BaudRate = (uint)settings.BaudRate;
        dcb.ByteSize = (byte)settings.DataBits;
        dcb.Parity = settings.Parity switch
        {
            SerialParity.Odd => Kernel32.Dcb.OddParity,
            SerialParity.Even => Kernel32.Dcb.EvenParity,
            _ => Kernel32.Dcb.NoParity,
        };
        dcb.StopBits = settings.StopBits == SerialStopBits.Two ? Kernel32.Dcb.TwoStopBits : Kernel32.Dcb.OneStopBit;

        // Binary mode, keep NUL bytes (Zaber data contains them), never abort I/O on a line error, DTR on.
        var flags = Kernel32.Dcb.FlagBinary | Kernel32.Dcb.DtrControlEnable | Kernel32.Dcb.FlagTxContinueOnXoff;
        if (settings.Parity != SerialParity.None)
        {
            flags |= Kernel32.Dcb.FlagParity;
        }

        flags |= settings.Handshake switch
        {
            SerialHandshake.RequestToSend => Kernel32.Dcb.FlagOutxCtsFlow | Kernel32.Dcb.RtsControlHandshake,
            SerialHandshake.XOnXOff => Kernel32.Dcb.FlagOutX | Kernel32.Dcb.FlagInX | Kernel32.Dcb.RtsControlEnable,
            _ => Kernel32.Dcb.RtsControlEnable,
        };
        dcb.Flags = flags;
        dcb.XonChar = 0x11;
        dcb.XoffChar = 0x13;
        if (!Kernel32.SetCommState(handle, &dcb))
        {
            throw new SerialPortException(name, $"{name}: cannot apply {settings}: {Marshal.GetPInvokeErrorMessage(Marshal.GetLastPInvokeError())}");
        }

        Kernel32.SetupComm(handle, 4096, 4096);

        // MAXDWORD, MAXDWORD, n: a read returns as soon as one byte is there, or after n ms with none.
        var timeouts = new Kernel32.CommTimeouts
        {
            ReadIntervalTimeout = Kernel32.MaxDword,
            ReadTotalTimeoutMultiplier = Kernel32.MaxDword,
            ReadTotalTimeoutConstant = ReadPollMs,
            WriteTotalTimeoutMultiplier = 0,
            WriteTotalTimeoutConstant = WriteTimeoutMs,
        };
        if (!Kernel32.SetCommTimeouts(handle, &timeouts))
        {
            throw new SerialPortException(name, $"{name}: cannot set timeouts: {Marshal.GetPInvokeErrorMessage(Marshal.GetLastPInvokeError())}");
        }

        Kernel32.PurgeComm(handle, Kernel32.PurgeRxAbort | Kernel32.PurgeTxAbort | Kernel32.PurgeRxClear | Kernel32.PurgeTxClear);
    }

    private IOException Failure(string what, int error) =>
        new($"{_name}: {what} failed: {Marshal.GetPInvokeErrorMessage(error)} (the port was unplugged or closed)");
}
