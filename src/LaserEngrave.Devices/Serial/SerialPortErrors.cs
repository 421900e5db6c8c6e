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

    public static SerialPortException FromWin32(string name, int error) => error switch
    {
        Kernel32.ErrorFileNotFound or Kernel32.ErrorPathNotFound => NoSuchPort(name),

        // Windows answers "access denied" when another program holds the port open.
        Kernel32.ErrorAccessDenied or Kernel32.ErrorSharingViolation => InUse(name),
        _ => new SerialPortException(name, $"{name}: cannot open: {Marshal.GetPInvokeErrorMessage(error)}"),
    };
}
