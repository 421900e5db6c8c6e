using System.ComponentModel;
using LaserEngrave.App.Services;

namespace LaserEngrave.App.Web;

/// <summary>Opens a URL in the user's default browser.</summary>
internal static class BrowserLauncher
{
    public static bool TryOpen(string url)
    {
        try
        {
            SystemShell.Open(url);
            return true;
        }
        catch (Exception ex) when (ex is Win32Exception or InvalidOperationException)
        {
            return false;
        }
    }
}
