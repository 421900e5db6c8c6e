using System.Runtime.InteropServices;
using LaserEngrave.Devices.Serial.Unix;
using LaserEngrave.Devices.Serial.Windows;

namespace LaserEngrave.Devices.Serial;

/// <summary>The one-line messages for a port that cannot be opened, from an errno (Unix) or a Win32 error.</summary>
internal static class SerialPortErrors
{
    public static SerialPortException NoSuchPort(string name) => new(name, $"{name}: no such port");

    public static SerialPortException InUse(string name) => new(name, $"{name}: port is in use by another program");

    public static SerialPortException PermissionDenied(string name) =>
        new(name, $"{name}: permission denied (on Linux add the user to the dialout group)");

    public static SerialPortException NotASerialPort(string name) => new(name, $"{name}: not a serial port");

    public static SerialPortException FromErrno(string name, int errno) => errno switch
    {
        UnixPlatform.ErrNoEntry or UnixPlatform.ErrNoDeviceOrAddress or UnixPlatform.ErrNoDevice => NoSuchPort(name),
        UnixPlatform.ErrBusy => InUse(name),
        UnixPlatform.ErrAccess or UnixPlatform.ErrPermission => PermissionDenied(name),
        UnixPlatform.ErrNotTty or UnixPlatform.ErrIsDirectory => NotASerialPort(name),
        _ => new SerialPortException(name, $"{name}: cannot open: {Marshal.GetPInvokeErrorMessage(errno)}"),
    };

    /// <summary>The message for a failed <see cref="System.IO.Ports.SerialPort.Open"/>.</summary>
    public static SerialPortException FromOpenFailure(string name, Exception error) => error switch
    {
        // On Unix System.IO.Ports answers every failed open with "access denied" around an IOException whose HResult
        // is the errno.
        UnauthorizedAccessException { InnerException: IOException inner } when !OperatingSystem.IsWindows() => FromErrno(name, inner.HResult),

        // Windows answers "access denied" when another program holds the port open.
        UnauthorizedAccessException when OperatingSystem.IsWindows() => InUse(name),
        IOException or ArgumentException when OperatingSystem.IsWindows()
            && !System.IO.Ports.SerialPort.GetPortNames().Contains(name, StringComparer.OrdinalIgnoreCase) => NoSuchPort(name),
        _ => new SerialPortException(name, $"{name}: cannot open: {error.Message}"),
    };

    public static SerialPortException FromWin32(string name, int error) => error switch
    {
        Kernel32.ErrorFileNotFound or Kernel32.ErrorPathNotFound => NoSuchPort(name),

        // Windows answers "access denied" when another program holds the port open.
        Kernel32.ErrorAccessDenied or Kernel32.ErrorSharingViolation => InUse(name),
        _ => new SerialPortException(name, $"{name}: cannot open: {Marshal.GetPInvokeErrorMessage(error)}"),
    };
}
