using System.Runtime.InteropServices;
using Microsoft.Win32.SafeHandles;

namespace LaserEngrave.Devices.Serial.Windows;

/// <summary>The Win32 comm API calls a serial port needs.</summary>
internal static unsafe partial class Kernel32
{
    public const uint GenericRead = 0x80000000;
    public const uint GenericWrite = 0x40000000;
    public const uint OpenExisting = 3;
    public const uint FileFlagOverlapped = 0x40000000;
    public const uint FileTypeChar = 0x0002;

    public const int ErrorFileNotFound = 2;
    public const int ErrorPathNotFound = 3;
    public const int ErrorAccessDenied = 5;
    public const int ErrorSharingViolation = 32;
    public const int ErrorOperationAborted = 995;
    public const int ErrorIoPending = 997;

    public const uint PurgeTxAbort = 0x0001;
    public const uint PurgeRxAbort = 0x0002;
    public const uint PurgeTxClear = 0x0004;
    public const uint PurgeRxClear = 0x0008;

    public const uint MaxDword = 0xFFFFFFFF;

    [LibraryImport("kernel32.dll", EntryPoint = "CreateFileW", StringMarshalling = StringMarshalling.Utf16, SetLastError = true)]
    public static partial SafeFileHandle CreateFile(
        string fileName, uint desiredAccess, uint shareMode, nint securityAttributes, uint creationDisposition, uint flagsAndAttributes, nint templateFile);

    [LibraryImport("kernel32.dll", SetLastError = true)]
    public static partial uint GetFileType(SafeFileHandle file);

    [LibraryImport("kernel32.dll", SetLastError = true)]
    [return: MarshalAs(UnmanagedType.Bool)]
    public static partial bool GetCommState(SafeFileHandle file, Dcb* dcb);

    [LibraryImport("kernel32.dll", SetLastError = true)]
    [return: MarshalAs(UnmanagedType.Bool)]
    public static partial bool SetCommState(SafeFileHandle file, Dcb* dcb);

    [LibraryImport("kernel32.dll", SetLastError = true)]
    [return: MarshalAs(UnmanagedType.Bool)]
    public static partial bool SetCommTimeouts(SafeFileHandle file, CommTimeouts* timeouts);

    [LibraryImport("kernel32.dll", SetLastError = true)]
    [return: MarshalAs(UnmanagedType.Bool)]
    public static partial bool SetupComm(SafeFileHandle file, uint inQueue, uint outQueue);

    [LibraryImport("kernel32.dll", SetLastError = true)]
    [return: MarshalAs(UnmanagedType.Bool)]
    public static partial bool PurgeComm(SafeFileHandle file, uint flags);

    [LibraryImport("kernel32.dll", SetLastError = true)]
    [return: MarshalAs(UnmanagedType.Bool)]
    public static partial bool ReadFile(SafeFileHandle file, byte* buffer, uint count, uint* read, NativeOverlapped* overlapped);

    [LibraryImport("kernel32.dll", SetLastError = true)]
    [return: MarshalAs(UnmanagedType.Bool)]
    public static partial bool WriteFile(SafeFileHandle file, byte* buffer, uint count, uint* written, NativeOverlapped* overlapped);

    [LibraryImport("kernel32.dll", SetLastError = true)]
    [return: MarshalAs(UnmanagedType.Bool)]
    public static partial bool GetOverlappedResult(SafeFileHandle file, NativeOverlapped* overlapped, uint* transferred, [MarshalAs(UnmanagedType.Bool)] bool wait);

    [LibraryImport("kernel32.dll", SetLastError = true)]
    [return: MarshalAs(UnmanagedType.Bool)]
    public static partial bool CancelIoEx(SafeFileHandle file, NativeOverlapped* overlapped);

    /// <summary>Win32 DCB (28 bytes); the 1- and 2-bit fields of the C struct live in <see cref="Flags"/>.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Dcb
    {
        public const uint FlagBinary = 1u << 0;
        public const uint FlagParity = 1u << 1;
        public const uint FlagOutxCtsFlow = 1u << 2;
        public const uint FlagOutxDsrFlow = 1u << 3;
        public const uint DtrControlMask = 3u << 4;
        public const uint DtrControlEnable = 1u << 4;
        public const uint FlagDsrSensitivity = 1u << 6;
        public const uint FlagTxContinueOnXoff = 1u << 7;
        public const uint FlagOutX = 1u << 8;
        public const uint FlagInX = 1u << 9;
        public const uint FlagErrorChar = 1u << 10;
        public const uint FlagNull = 1u << 11;
        public const uint RtsControlMask = 3u << 12;
        public const uint RtsControlEnable = 1u << 12;
        public const uint RtsControlHandshake = 2u << 12;
        public const uint FlagAbortOnError = 1u << 14;

        public const byte NoParity = 0;
        public const byte OddParity = 1;
        public const byte EvenParity = 2;
        public const byte OneStopBit = 0;
        public const byte TwoStopBits = 2;

        public uint DcbLength;
        public uint BaudRate;
        public uint Flags;
        public ushort Reserved;
        public ushort XonLim;
        public ushort XoffLim;
        public byte ByteSize;
        public byte Parity;
        public byte StopBits;
        public byte XonChar;
        public byte XoffChar;
        public byte ErrorChar;
        public byte EofChar;
        public byte EvtChar;
        public ushort Reserved1;
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct CommTimeouts
    {
        public uint ReadIntervalTimeout;
        public uint ReadTotalTimeoutMultiplier;
        public uint ReadTotalTimeoutConstant;
        public uint WriteTotalTimeoutMultiplier;
        public uint WriteTotalTimeoutConstant;
    }
}
