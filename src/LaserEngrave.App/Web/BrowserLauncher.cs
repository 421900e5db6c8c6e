using System.ComponentModel;
using System.Diagnostics;
using LaserEngrave.App.Services;

namespace LaserEngrave.App.Web;

/// <summary>
/// Opens the page in its own window: Edge's, Chrome's or Chromium's app mode (no tabs, no address bar, its own profile
/// so it is its own process), else the default browser; either is given the launch file, never the token.
/// </summary>
internal static class BrowserLauncher
{
    /// <summary>
    /// Opens the page through <paramref name="launchFile"/> (a file of the user's alone that sends the browser on with a
    /// one-time code): the browser's command line, which every local user can read, names only the file. False when
    /// nothing could open it.
    /// </summary>
    public static bool TryOpen(string launchFile, string profileFolder)
    {
        ArgumentNullException.ThrowIfNull(launchFile);
        if (FindAppBrowser(Candidates(), File.Exists) is { } browser)
        {
            try
            {
                var start = new ProcessStartInfo(browser) { UseShellExecute = false };
                foreach (var argument in AppModeArguments(new Uri(launchFile).AbsoluteUri, profileFolder, asRoot: OperatingSystem.IsLinux() && Environment.IsPrivilegedProcess))
                {
                    start.ArgumentList.Add(argument);
                }

                using var process = Process.Start(start);
                return true;
            }
            catch (Exception ex) when (ex is Win32Exception or InvalidOperationException)
            {
                // Fall through to the default browser.
            }
        }

        try
        {
            // The default browser opens the .html file as it opens any (the shell, open, xdg-open).
            SystemShell.Open(launchFile);
            return true;
        }
        catch (Exception ex) when (ex is Win32Exception or InvalidOperationException)
        {
            return false;
        }
    }

    /// <summary>
    /// The window's first size, in the screen's scaled pixels: it fits the usable area of common laptop screens (1280 x 800,
    /// 1366 x 768, and 1920 x 1080 at 150 %, which is 1280 x 720, less a taskbar or menu bar); 1400 x 900 overflowed
    /// them. The page is laid out for 1280 x 720 and down to 800 x 600, and the window can be made larger by hand.
    /// </summary>
    public static (int Width, int Height) WindowSize { get; } = (1280, 660);

    /// <summary>The arguments of an app-mode window with its own profile (so it opens a window of its own, not a tab).</summary>
    /// <remarks>
    /// Chromium refuses to start as root on Linux unless told to run without its sandbox: then (a lab PC where the app
    /// runs as root for the serial ports) the window shows only the app's own page on this computer, so it is told.
    /// </remarks>
    public static IReadOnlyList<string> AppModeArguments(string url, string profileFolder, bool asRoot = false) =>
        ["--app=" + url, "--user-data-dir=" + profileFolder, "--no-first-run", "--no-default-browser-check",
            $"--window-size={WindowSize.Width},{WindowSize.Height}", .. asRoot ? ["--no-sandbox"] : Array.Empty<string>()];

    /// <summary>The first candidate that exists.</summary>
    public static string? FindAppBrowser(IEnumerable<string> candidates, Func<string, bool> exists) => candidates.FirstOrDefault(exists);

    /// <summary>Where Edge, Chrome and Chromium live on this system, most likely first (Edge comes with Windows).</summary>
    public static IEnumerable<string> Candidates()
    {
        if (OperatingSystem.IsWindows())
        {
            foreach (var root in new[] { Environment.SpecialFolder.ProgramFilesX86, Environment.SpecialFolder.ProgramFiles, Environment.SpecialFolder.LocalApplicationData })
            {
                var folder = Environment.GetFolderPath(root);
                if (folder.Length > 0)
                {
                    yield return Path.Combine(folder, "Microsoft", "Edge", "Application", "msedge.exe");
                    yield return Path.Combine(folder, "Google", "Chrome", "Application", "chrome.exe");
                }
            }

            yield break;
        }

        if (OperatingSystem.IsMacOS())
        {
            yield return "/Applications/Microsoft Edge.app/Contents/MacOS/Microsoft Edge";
            yield return "/Applications/Google Chrome.app/Contents/MacOS/Google Chrome";
            yield return "/Applications/Chromium.app/Contents/MacOS/Chromium";
            yield break;
        }

        var path = Environment.GetEnvironmentVariable("PATH") ?? string.Empty;
        foreach (var name in new[] { "chromium", "chromium-browser", "google-chrome", "google-chrome-stable", "microsoft-edge", "microsoft-edge-stable" })
        {
            foreach (var folder in path.Split(Path.PathSeparator, StringSplitOptions.RemoveEmptyEntries))
            {
                yield return Path.Combine(folder, name);
            }
        }
    }
}
