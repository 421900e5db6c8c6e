namespace LaserEngrave.App.Services;

/// <summary>The real <see cref="IFileAccess"/>: uploads under <see cref="AppFolders.UploadFolder"/>, folders opened by the shell.</summary>
/// <param name="maxUploadBytes">The upload limit; the app's <see cref="IFileAccess.MaxUploadBytes"/> except in tests.</param>
public sealed class FileAccess(AppFolders folders, long maxUploadBytes = IFileAccess.MaxUploadBytes) : IFileAccess
{
    public async Task<string> SaveUploadAsync(string fileName, Stream content, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(content);

        // Only the name's last part is kept, so an upload cannot write outside the image folder.
        var name = Path.GetFileName(fileName);
        if (string.IsNullOrWhiteSpace(name))
        {
            name = "image";
        }

        if (UploadNameProblem(name) is { } problem)
        {
            throw new UploadException(Printable(name), problem);
        }

        Directory.CreateDirectory(folders.UploadFolder);
        var path = Path.Combine(folders.UploadFolder, name);

        // Written under a temporary name and moved into place only when whole: a failed upload leaves nothing behind.
        var partial = Path.Combine(folders.UploadFolder, $".{name}.{Path.GetRandomFileName()}.part");
        try
        {
            var file = File.Create(partial);
            await using (file.ConfigureAwait(false))
            {
                var buffer = new byte[81920];
                long total = 0;
                int read;
                while ((read = await content.ReadAsync(buffer, cancellationToken).ConfigureAwait(false)) > 0)
                {
                    total += read;
                    if (total > maxUploadBytes)
                    {
                        throw new UploadException(name, TooLargeFor(maxUploadBytes));
                    }

                    await file.WriteAsync(buffer.AsMemory(0, read), cancellationToken).ConfigureAwait(false);
                }
            }

            File.Move(partial, path, overwrite: true);
            return path;
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException or OperationCanceledException or UploadException)
        {
            File.Delete(partial);
            throw ex switch
            {
                UploadException => ex,
                OperationCanceledException => new UploadException(name, "the upload was interrupted", ex),
                _ when IsBodyTooLarge(ex) => new UploadException(name, TooLargeFor(maxUploadBytes), ex),
                _ => new UploadException(name, ex.Message, ex),
            };
        }
    }

    /// <summary>Why <paramref name="name"/> cannot name a file in the image folder, in the user's words; null when it can.</summary>
    private static string? UploadNameProblem(string name) =>
        name is "." or ".." ? "not a file name"
        : name.Any(c => char.IsControl(c) || c is '/' or '\\' || Array.IndexOf(Path.GetInvalidFileNameChars(), c) >= 0) ? "the name has a character a file name cannot have"
        : name.Length > IFileAccess.MaxUploadNameLength || System.Text.Encoding.UTF8.GetByteCount(name) > IFileAccess.MaxUploadNameLength
            ? $"the name is longer than {IFileAccess.MaxUploadNameLength} characters"
        : null;

    /// <summary>A name as a message can show it: control characters as '?', at most 60 characters.</summary>
    private static string Printable(string name)
    {
        var shown = new string([.. name.Select(c => char.IsControl(c) ? '?' : c)]);
        return shown.Length <= 60 ? shown : shown[..57] + "...";
    }

    public void RemoveUpload(string path)
    {
        ArgumentNullException.ThrowIfNull(path);
        var full = Path.GetFullPath(path);
        if (!string.Equals(Path.GetDirectoryName(full), Path.GetFullPath(folders.UploadFolder), StringComparison.Ordinal))
        {
            return;
        }

        try
        {
            File.Delete(full);
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            // Left behind only if the folder cannot be written; the open failure is what the user is told.
        }
    }

    /// <summary>The app's one rule for uploads, in its words.</summary>
    public static string TooLarge => TooLargeFor(IFileAccess.MaxUploadBytes);

    private static string TooLargeFor(long bytes) => $"the file is larger than {(bytes >= 1 << 20 ? $"{bytes >> 20} MB" : $"{bytes} bytes")}, the most the app takes";

    // Kestrel's own limit surfaces as a bad request with status 413 while the body is read.
    private static bool IsBodyTooLarge(Exception ex) => ex is Microsoft.AspNetCore.Http.BadHttpRequestException { StatusCode: 413 };

    public bool Exists(string path) => File.Exists(path);

    public IReadOnlyList<string> SampleImages() =>
        Directory.Exists(folders.SamplesFolder)
            ? [.. Directory.EnumerateFiles(folders.SamplesFolder).Order(StringComparer.OrdinalIgnoreCase)]
            : [];

    public string SavePattern(string name, Core.Imaging.BitMask mask)
    {
        var folder = Path.Combine(folders.UploadFolder, "patterns");
        Directory.CreateDirectory(folder);
        var path = Path.Combine(folder, name + ".png");
        Core.Imaging.PngWriter.WriteMask(path, mask);
        return path;
    }

    public bool OpenFolder(string path)
    {
        Directory.CreateDirectory(path);
        if (!HasDesktop(Environment.GetEnvironmentVariable))
        {
            return false;
        }

        SystemShell.Open(path);
        return true;
    }

    /// <summary>
    /// Whether a file manager's window can appear: always on Windows and macOS; elsewhere only in an X11 or Wayland
    /// session, since xdg-open without one starts and shows nothing (a server, ssh, a container).
    /// </summary>
    internal static bool HasDesktop(Func<string, string?> environment) =>
        OperatingSystem.IsWindows() || OperatingSystem.IsMacOS()
        || !string.IsNullOrEmpty(environment("DISPLAY")) || !string.IsNullOrEmpty(environment("WAYLAND_DISPLAY"));
}
