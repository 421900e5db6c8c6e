using System.ComponentModel;
using System.Diagnostics;

namespace LaserEngrave.App.Web;

/// <summary>Opens a URL in the user's default browser.</summary>
internal static class BrowserLauncher
{
    public static bool TryOpen(string url)
    {
        try
        {
            var start = OperatingSystem.IsWindows() ? new ProcessStartInfo(url) { UseShellExecute = true }
                : OperatingSystem.IsMacOS() ? new ProcessStartInfo("open", url)
                : new ProcessStartInfo("xdg-open", url);
            using var process = Process.Start(start);
            return process is not null || OperatingSystem.IsWindows();
        }
        catch (Exception ex) when (ex is Win32Exception or InvalidOperationException)
        {
            return false;
        }
    }
}
