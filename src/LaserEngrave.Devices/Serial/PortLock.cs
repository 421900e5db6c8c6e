using System.Runtime.InteropServices;
using Microsoft.Win32.SafeHandles;

namespace LaserEngrave.Devices.Serial;

/// <summary>
/// An exclusive lock on a serial device itself (Linux, macOS): flock on a descriptor of the device, held while the
/// link is open and gone with it, so no lock file exists anywhere (no file in /tmp another user could create first, or
/// plant as a symbolic link for a root-run app to follow).
/// </summary>
/// <remarks>
/// The descriptor is opened before System.IO.Ports opens the port, read-only, non-blocking and without becoming the
/// controlling terminal (O_NOCTTY: a hang-up would otherwise end a service), so a second program finds the lock taken
/// before it has changed the port's settings or modem lines under a run. Only a program that can open the device at
/// all can lock it, and such a program could use the port anyway. System.IO.Ports' TIOCEXCL keeps other users out too,
/// but not root: the lock is what keeps a second LaserEngrave run as root out.
/// </remarks>
internal static class PortLock
{
    private const int LockEx = 2;
    private const int LockNb = 4;
    private const int ENoEnt = 2;
    private const int EIntr = 4;
    private const int EBusy = 16;

    /// <summary>
    /// Locks <paramref name="device"/> (the device's own path, links resolved); null where the device could not be opened
    /// for the lock for a reason the port's own open reports better (permissions, not a device).
    /// </summary>
    /// <exception cref="SerialPortException">The device does not exist, or another program holds it.</exception>
    public static SafeFileHandle? Take(string device, string name)
    {
        var macOs = OperatingSystem.IsMacOS();
        var flags = macOs ? 0x20000 | 0x4 | 0x1000000 : 0x100 | 0x800 | 0x80000; // O_NOCTTY | O_NONBLOCK | O_CLOEXEC, read-only
        int fd;
        do
        {
            fd = NativeMethods.Open(device, flags);
        }
        while (fd < 0 && Marshal.GetLastPInvokeError() == EIntr);

        if (fd < 0)
        {
            return Marshal.GetLastPInvokeError() switch
            {
                ENoEnt => throw SerialPortErrors.NoSuchPort(name),
                // TIOCEXCL of the program that has the port open: in use.
                EBusy => throw SerialPortErrors.InUse(name),
                _ => null,
            };
        }

        var handle = new SafeFileHandle(fd, ownsHandle: true);
        int locked;
        do
        {
            locked = NativeMethods.Flock(fd, LockEx | LockNb);
        }
        while (locked < 0 && Marshal.GetLastPInvokeError() == EIntr);

        if (locked < 0)
        {
            handle.Dispose();
            throw SerialPortErrors.InUse(name);
        }

        return handle;
    }

    private static class NativeMethods
    {
        [DllImport("libc", EntryPoint = "open", SetLastError = true)]
        [DefaultDllImportSearchPaths(DllImportSearchPath.SafeDirectories)]
        public static extern int Open([MarshalAs(UnmanagedType.LPUTF8Str)] string path, int flags);

        [DllImport("libc", EntryPoint = "flock", SetLastError = true)]
        [DefaultDllImportSearchPaths(DllImportSearchPath.SafeDirectories)]
        public static extern int Flock(int fd, int operation);
    }
}
