using System.Runtime.InteropServices;

namespace LaserEngrave.Core.IO;

/// <summary>Tells whether a path the user gave is a regular file, before anything opens it.</summary>
/// <remarks>
/// Opening a FIFO for reading blocks until something writes to it, and a device or a folder is never an image, a
/// profile or a log, so every file LaserEngrave reads is checked here first. .NET has no public file-type query on
/// Unix, so this asks the runtime's own native shim (SystemNative_Stat, which follows symbolic links and reports the
/// type bits the same way on every Unix).
/// </remarks>
public static class RegularFile
{
    private const int FileTypeMask = 0xF000;
    private const int Fifo = 0x1000;
    private const int CharacterDevice = 0x2000;
    private const int Directory = 0x4000;
    private const int BlockDevice = 0x6000;
    private const int Regular = 0x8000;
    private const int Socket = 0xC000;

    /// <summary>
    /// Null when <paramref name="path"/> is a regular file or does not exist (the caller reports a missing file in its
    /// own words); otherwise what it is instead, e.g. "is a named pipe (FIFO), not a regular file".
    /// </summary>
    public static string? Problem(string path)
    {
        ArgumentException.ThrowIfNullOrEmpty(path);
        if (System.IO.Directory.Exists(path))
        {
            return "is a folder, not a file";
        }

        if (OperatingSystem.IsWindows())
        {
            return null;
        }

        if (Stat(path, out var status) != 0)
        {
            return null;
        }

        return (status.Mode & FileTypeMask) switch
        {
            Regular => null,
            Fifo => "is a named pipe (FIFO), not a regular file",
            CharacterDevice => "is a character device, not a regular file",
            BlockDevice => "is a block device, not a regular file",
            Directory => "is a folder, not a file",
            Socket => "is a socket, not a regular file",
            _ => "is not a regular file",
        };
    }

    [DllImport("libSystem.Native", EntryPoint = "SystemNative_Stat", SetLastError = true)]
    [DefaultDllImportSearchPaths(DllImportSearchPath.SafeDirectories)]
    private static extern int Stat([MarshalAs(UnmanagedType.LPUTF8Str)] string path, out FileStatus status);

    /// <summary>The head of the runtime's FileStatus record (flags, then mode), padded well past its full length so the shim's write stays inside it.</summary>
    [StructLayout(LayoutKind.Sequential, Size = 256)]
    private struct FileStatus
    {
        public int Flags;

        public int Mode;
    }
}
