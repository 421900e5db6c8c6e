using System.IO.Ports;
using System.Runtime.InteropServices;

namespace LaserEngrave.Devices.Serial;

/// <summary>The one-line messages for a port that cannot be opened.</summary>
internal static class SerialPortErrors
{
    // errno values, the same on Linux and macOS.
    private const int ErrPermission = 1;
    private const int ErrNoEntry = 2;
    private const int ErrNoDeviceOrAddress = 6;
    private const int ErrAccess = 13;
    private const int ErrBusy = 16;
    private const int ErrNoDevice = 19;
    private const int ErrIsDirectory = 21;
    private const int ErrNotTty = 25;

    public static SerialPortException NoSuchPort(string name) => new(name, $"{name}: no such port");

    public static SerialPortException InUse(string name) => new(name, $"{name}: port is in use by another program");

    public static SerialPortException PermissionDenied(string name) =>
        new(name, $"{name}: permission denied (on Linux add the user to the dialout group)");

    public static SerialPortException NotASerialPort(string name) => new(name, $"{name}: not a serial port");

    /// <summary>The message for a failed <see cref="SerialPort.Open"/>.</summary>
    public static SerialPortException FromOpenFailure(string name, Exception error) => error switch
    {
        // On Unix System.IO.Ports answers every failed open with "access denied" around an IOException whose HResult
        // is the errno.
        UnauthorizedAccessException { InnerException: IOException inner } when !OperatingSystem.IsWindows() => FromErrno(name, inner.HResult),

        // Windows answers "access denied" when another program holds the port open.
        UnauthorizedAccessException when OperatingSystem.IsWindows() => InUse(name),
        IOException or ArgumentException when OperatingSystem.IsWindows()
            && !SerialPort.GetPortNames().Contains(name, StringComparer.OrdinalIgnoreCase) => NoSuchPort(name),
        _ => new SerialPortException(name, $"{name}: cannot open: {error.Message}"),
    };

    public static SerialPortException FromErrno(string name, int errno) => errno switch
    {
        ErrNoEntry or ErrNoDeviceOrAddress or ErrNoDevice => NoSuchPort(name),
        ErrBusy => InUse(name),
        ErrAccess or ErrPermission => PermissionDenied(name),
        ErrNotTty or ErrIsDirectory => NotASerialPort(name),
        _ => new SerialPortException(name, $"{name}: cannot open: {Marshal.GetPInvokeErrorMessage(errno)}"),
    };
}
