using System.Runtime.InteropServices;

namespace LaserEngrave.App.Services;

/// <summary>Whether a path is a regular file: a FIFO, a device or a socket would block (or never end) the read that opens it.</summary>
internal static class RegularFile
{
    private const int TypeMask = 0xF000;
    private const int Regular = 0x8000;

    /// <summary>Null when <paramref name="path"/> is a regular file; otherwise what it is, for a one-line refusal.</summary>
    public static string? Problem(string path)
    {
        if (Directory.Exists(path))
        {
            return "is a folder, not an image file";
        }

        if (!File.Exists(path))
        {
            return "no such file";
        }

        if (OperatingSystem.IsWindows())
        {
            // Windows keeps pipes and devices out of the file system's folders.
            return null;
        }

        // The runtime's own stat (the one FileInfo uses), asked for the file type it keeps to itself.
        var status = new byte[256];
        if (Stat(path, status) != 0)
        {
            return "cannot be examined";
        }

        var mode = BitConverter.ToInt32(status, 4);
        return (mode & TypeMask) == Regular ? null : "is not a regular file (a pipe, device or socket): only image files are opened";
    }

    [DllImport("libSystem.Native", EntryPoint = "SystemNative_Stat")]
    [DefaultDllImportSearchPaths(DllImportSearchPath.SafeDirectories)]
    private static extern int Stat([MarshalAs(UnmanagedType.LPUTF8Str)] string path, [Out] byte[] status);
}
