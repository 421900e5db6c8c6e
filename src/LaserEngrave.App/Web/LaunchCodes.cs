using System.Security.Cryptography;
using System.Text;

namespace LaserEngrave.App.Web;

/// <summary>
/// One-time codes that open the page: the window's address carries one, never the start's token, and the page trades it
/// for the token once (<c>POST /api/session</c>). A code is refused after its first use, so what a browser's history, a
/// synced profile or a start line keeps of it opens nothing.
/// </summary>
/// <remarks>
/// The window itself is started on a launch file readable by the user alone (<see cref="WriteLaunchFile"/>), so the code
/// is on no command line: another local user who reads the browser's arguments (<c>/proc/PID/cmdline</c>, <c>ps</c>)
/// finds only the file's name.
/// </remarks>
public sealed class LaunchCodes
{
    /// <summary>The header in which the page shows its launch code to <c>POST /api/session</c>.</summary>
    public const string HeaderName = "X-LaserEngrave-Launch";

    /// <summary>Where the page's address carries the code: the fragment (never sent to a server, not in a Referer).</summary>
    public const string FragmentName = "launch";

    /// <summary>At most this many codes wait for their use; the oldest is dropped first (a code is for one window opening now).</summary>
    private const int MaxWaiting = 16;

    private readonly Lock _lock = new();
    private readonly List<(string Code, string? File)> _waiting = [];

    /// <summary>A new code (128 random bits, URL-safe) that opens the page once.</summary>
    public string Issue() => Add(null);

    /// <summary>
    /// Writes a page that sends the browser to <paramref name="address"/> with a new code into <paramref name="folder"/>,
    /// created readable and writable by the user alone (the folder too, on Unix), and answers its path; the file is
    /// removed when its code is used (or at exit, <see cref="RemoveFiles"/>).
    /// </summary>
    /// <exception cref="IOException">The folder cannot be written.</exception>
    public string WriteLaunchFile(string folder, string address)
    {
        ArgumentNullException.ThrowIfNull(address);
        if (OperatingSystem.IsWindows())
        {
            // Under the user's profile (the data folder), which only the user and administrators can read.
            Directory.CreateDirectory(folder);
        }
        else
        {
            Directory.CreateDirectory(folder, UnixFileMode.UserRead | UnixFileMode.UserWrite | UnixFileMode.UserExecute);
            File.SetUnixFileMode(folder, UnixFileMode.UserRead | UnixFileMode.UserWrite | UnixFileMode.UserExecute);
        }

        var path = Path.Combine(folder, "launch-" + Path.GetRandomFileName().Replace(".", string.Empty, StringComparison.Ordinal) + ".html");
        var code = Add(path);
        var target = $"{address.TrimEnd('/')}/#{FragmentName}={code}";
        var options = new FileStreamOptions { Mode = FileMode.CreateNew, Access = FileAccess.Write };
        if (!OperatingSystem.IsWindows())
        {
            options.UnixCreateMode = UnixFileMode.UserRead | UnixFileMode.UserWrite;
        }

        using var file = new FileStream(path, options);
        // A refresh, not a script: it works with scripts off for file pages, and the link is there if a browser stops.
        file.Write(Encoding.UTF8.GetBytes(
            "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><meta name=\"referrer\" content=\"no-referrer\">\n" +
            $"<meta http-equiv=\"refresh\" content=\"0;url={target}\"><title>LaserEngrave</title></head>\n" +
            $"<body><p><a href=\"{target}\">Open LaserEngrave</a></p></body></html>\n"));
        return path;
    }

    /// <summary>Whether <paramref name="code"/> is a code issued and not yet used; it is used by this call (and its launch file removed).</summary>
    public bool Redeem(string? code)
    {
        if (string.IsNullOrEmpty(code))
        {
            return false;
        }

        var given = Encoding.ASCII.GetBytes(code);
        string? file;
        lock (_lock)
        {
            var at = _waiting.FindIndex(w => CryptographicOperations.FixedTimeEquals(Encoding.ASCII.GetBytes(w.Code), given));
            if (at < 0)
            {
                return false;
            }

            file = _waiting[at].File;
            _waiting.RemoveAt(at);
        }

        Delete(file);
        return true;
    }

    /// <summary>Removes the launch files of codes never used (at exit).</summary>
    public void RemoveFiles()
    {
        List<string?> files;
        lock (_lock)
        {
            files = [.. _waiting.Select(w => w.File)];
            _waiting.Clear();
        }

        foreach (var file in files)
        {
            Delete(file);
        }
    }

    private string Add(string? file)
    {
        var code = Convert.ToBase64String(RandomNumberGenerator.GetBytes(16)).TrimEnd('=').Replace('+', '-').Replace('/', '_');
        string? dropped = null;
        lock (_lock)
        {
            if (_waiting.Count >= MaxWaiting)
            {
                dropped = _waiting[0].File;
                _waiting.RemoveAt(0);
            }

            _waiting.Add((code, file));
        }

        Delete(dropped);
        return code;
    }

    private static void Delete(string? file)
    {
        if (file is null)
        {
            return;
        }

        try
        {
            File.Delete(file);
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            // The code is refused from now on, so a file left behind opens nothing.
        }
    }
}
