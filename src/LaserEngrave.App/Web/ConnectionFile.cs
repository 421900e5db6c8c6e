using System.Text.Json;

namespace LaserEngrave.App.Web;

/// <summary>
/// The running app's address and token in a file beside its settings, readable by the user alone, so a script of the
/// same user finds the app: <c>{"url": "http://127.0.0.1:PORT", "token": "…", "pid": 1234}</c>. A script checks the
/// process is alive and that the server on the port proves it holds the token (<c>GET /api/proof</c>) before it sends
/// the token: a file left by a crash then sends nothing to whoever took the freed port.
/// </summary>
public static class ConnectionFile
{
    /// <summary>Writes the file whole (a new file, owner read and write only on Unix, moved into place).</summary>
    /// <exception cref="IOException">The data folder cannot be written.</exception>
    public static void Write(string path, string url, string token, int pid)
    {
        ArgumentNullException.ThrowIfNull(path);
        Directory.CreateDirectory(Path.GetDirectoryName(Path.GetFullPath(path))!);
        var partial = path + "." + Path.GetRandomFileName() + ".part";
        var options = new FileStreamOptions { Mode = FileMode.CreateNew, Access = FileAccess.Write };
        if (!OperatingSystem.IsWindows())
        {
            // Created 0600, never widened afterwards: no moment at which another local user could read the token.
            options.UnixCreateMode = UnixFileMode.UserRead | UnixFileMode.UserWrite;
        }

        try
        {
            using (var file = new FileStream(partial, options))
            {
                JsonSerializer.Serialize(file, new Connection(url, token) { Pid = pid });
            }

            File.Move(partial, path, overwrite: true);
        }
        catch
        {
            File.Delete(partial);
            throw;
        }
    }

    /// <summary>Removes the file at exit, if it still names this start (another start may have written it since).</summary>
    public static void Remove(string path, string token)
    {
        try
        {
            if (Read(path) is { } connection && connection.Token == token)
            {
                File.Delete(path);
            }
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            // A file left behind names a token no server takes any more.
        }
    }

    /// <summary>The address and token in the file; null when there is none or it is not one of these files.</summary>
    public static Connection? Read(string path)
    {
        if (!File.Exists(path))
        {
            return null;
        }

        try
        {
            return JsonSerializer.Deserialize<Connection>(File.ReadAllText(path));
        }
        catch (JsonException)
        {
            return null;
        }
    }

    /// <param name="Url">The app's address, e.g. http://127.0.0.1:41234, without the token.</param>
    /// <param name="Token">The start's token, for <c>Authorization: Bearer</c>.</param>
    public sealed record Connection(
        [property: System.Text.Json.Serialization.JsonPropertyName("url")] string Url,
        [property: System.Text.Json.Serialization.JsonPropertyName("token")] string Token)
    {
        /// <summary>The app's process id; 0 in a file of an earlier version.</summary>
        [System.Text.Json.Serialization.JsonPropertyName("pid")]
        public int Pid { get; init; }
    }
}
