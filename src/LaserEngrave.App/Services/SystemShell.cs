using System.Diagnostics;

namespace LaserEngrave.App.Services;

/// <summary>Opens a URL or a folder with what the system chooses for it (the default browser, the file manager).</summary>
/// <remarks>.NET's shell execute picks the opener per system (the shell on Windows, open on macOS, xdg-open and kin on Linux).</remarks>
internal static class SystemShell
{
    /// <summary>Opens <paramref name="target"/>; throws <see cref="System.ComponentModel.Win32Exception"/> when nothing can open it.</summary>
    public static void Open(string target)
    {
        using var process = Process.Start(new ProcessStartInfo(target) { UseShellExecute = true });
    }
}
