namespace LaserEngrave.App.Services;

/// <summary>The real <see cref="IFileAccess"/>: uploads under <see cref="AppFolders.UploadFolder"/> (content-addressed), folders opened by the shell.</summary>
/// <param name="maxUploadBytes">The upload limit; the app's <see cref="IFileAccess.MaxUploadBytes"/> except in tests.</param>
public sealed class FileAccess(AppFolders folders, long maxUploadBytes = IFileAccess.MaxUploadBytes) : IFileAccess
{
    /// <param name="quotaBytes">The most the image folder holds, all uploads together; the app's <see cref="IFileAccess.UploadQuotaBytes"/> except in tests.</param>
    public FileAccess(AppFolders folders, long maxUploadBytes, long quotaBytes)
        : this(folders, maxUploadBytes)
    {
        _quotaBytes = quotaBytes;
    }

    private readonly long _quotaBytes = IFileAccess.UploadQuotaBytes;

    /// <remarks>
    /// Content-addressed: the file goes to images/HASH/NAME, HASH the first 16 hex digits of its SHA-256, so an upload
    /// never replaces another's bytes (a run's source image stays as the run's log names it) and the same file sent
    /// twice is kept once. It is written under a temporary name and moved into place only when whole and once
    /// <paramref name="beforeCommit"/> (the run interlock) allows it: a refused or failed upload leaves nothing.
    /// </remarks>
    public async Task<string> SaveUploadAsync(string fileName, Stream content, CancellationToken cancellationToken, Action? beforeCommit = null)
    {
        ArgumentNullException.ThrowIfNull(content);
        var name = string.IsNullOrWhiteSpace(fileName) ? "image" : fileName;
        if (UploadNameProblem(name) is { } problem)
        {
            throw new UploadException(Printable(name), problem);
        }

        Directory.CreateDirectory(folders.UploadFolder);
        var partial = Path.Combine(folders.UploadFolder, $".upload.{Path.GetRandomFileName()}.part");
        var committed = false;
        try
        {
            using var hash = System.Security.Cryptography.IncrementalHash.CreateHash(System.Security.Cryptography.HashAlgorithmName.SHA256);
            long total = 0;
            var file = File.Create(partial);
            await using (file.ConfigureAwait(false))
            {
                var buffer = new byte[81920];
                int read;
                while ((read = await content.ReadAsync(buffer, cancellationToken).ConfigureAwait(false)) > 0)
                {
                    total += read;
                    if (total > maxUploadBytes)
                    {
                        throw new UploadException(name, TooLargeFor(maxUploadBytes));
                    }

                    hash.AppendData(buffer, 0, read);
                    await file.WriteAsync(buffer.AsMemory(0, read), cancellationToken).ConfigureAwait(false);
                }
            }

            var folder = Path.Combine(folders.UploadFolder, Convert.ToHexStringLower(hash.GetHashAndReset())[..16]);
            var path = Path.Combine(folder, name);
            beforeCommit?.Invoke();
            if (File.Exists(path))
            {
                // The same bytes under the same name: already kept, nothing replaced.
                return path;
            }

            if (HeldBytes() + total > _quotaBytes)
            {
                throw new UploadException(name, $"the image folder would hold more than {_quotaBytes >> 20} MB, the app's quota: remove images no longer needed from images/ in the app's data folder") { QuotaExceeded = true };
            }

            Directory.CreateDirectory(folder);
            File.Move(partial, path, overwrite: false);
            committed = true;
            return path;
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException or OperationCanceledException)
        {
            throw ex switch
            {
                UploadException => ex,
                OperationCanceledException => new UploadException(name, "the upload was interrupted", ex),
                _ when IsBodyTooLarge(ex) => new UploadException(name, TooLargeFor(maxUploadBytes), ex),
                _ => new UploadException(name, ex.Message, ex),
            };
        }
        finally
        {
            if (!committed)
            {
                File.Delete(partial);
            }
        }
    }

    /// <summary>The bytes the image folder holds now (uploads and patterns; unfinished uploads not counted).</summary>
    private long HeldBytes() =>
        new DirectoryInfo(folders.UploadFolder).EnumerateFiles("*", SearchOption.AllDirectories).Where(f => f.Extension != ".part").Sum(f => f.Length);

    /// <summary>Names Windows keeps for devices, with any extension (aux.bmp is AUX): a file of that name cannot be made or opened there.</summary>
    private static readonly HashSet<string> WindowsDeviceNames = new(
        ["CON", "PRN", "AUX", "NUL", "CONIN$", "CONOUT$", "COM¹", "COM²", "COM³", "LPT¹", "LPT²", "LPT³",
            .. Enumerable.Range(1, 9).SelectMany(i => new[] { $"COM{i}", $"LPT{i}" })],
        StringComparer.OrdinalIgnoreCase);

    /// <summary>
    /// Why <paramref name="name"/> cannot name a file in the image folder on any system the app runs on, in the user's
    /// words; null when it can. The same rules on Linux as on Windows, so a folder copied between them opens alike.
    /// </summary>
    private static string? UploadNameProblem(string name) =>
        name is "." or ".." ? "not a file name"
        : name.Contains('/', StringComparison.Ordinal) || name.Contains('\\', StringComparison.Ordinal) ? "a path, not a file name: send the file's name alone"
        : name.Any(c => char.IsControl(c) || c is '<' or '>' or ':' or '"' or '|' or '?' or '*' || Array.IndexOf(Path.GetInvalidFileNameChars(), c) >= 0)
            ? "the name has a character a file name cannot have"
        : name.FirstOrDefault(c => char.GetUnicodeCategory(c) == System.Globalization.UnicodeCategory.Format) is var format and not '\0'
            ? $"the name has an invisible formatting character (U+{(int)format:X4}), which can make it read as another name"
        : name.EndsWith('.') || name.EndsWith(' ') ? "the name ends in a dot or a space, which Windows drops"
        : WindowsDeviceNames.Contains(name.Split('.')[0].TrimEnd(' ')) ? "a name Windows keeps for a device (CON, NUL, AUX, COM1, LPT1...)"
        : name.Length > IFileAccess.MaxUploadNameLength || System.Text.Encoding.UTF8.GetByteCount(name) > IFileAccess.MaxUploadNameLength
            ? $"the name is longer than {IFileAccess.MaxUploadNameLength} characters"
        : null;

    /// <summary>A name as a message can show it: control and formatting characters as '?', at most 60 characters.</summary>
    private static string Printable(string name)
    {
        var shown = new string([.. name.Select(c => char.IsControl(c) || char.GetUnicodeCategory(c) == System.Globalization.UnicodeCategory.Format ? '?' : c)]);
        return shown.Length <= 60 ? shown : shown[..57] + "...";
    }

    public void RemoveUpload(string path)
    {
        ArgumentNullException.ThrowIfNull(path);
        var full = Path.GetFullPath(path);
        var folder = Path.GetDirectoryName(full);
        // An upload's own folder (images/HASH/) only: any other path is left alone.
        if (folder is null || !string.Equals(Path.GetDirectoryName(folder), Path.GetFullPath(folders.UploadFolder), StringComparison.Ordinal))
        {
            return;
        }

        try
        {
            File.Delete(full);
            if (!Directory.EnumerateFileSystemEntries(folder).Any())
            {
                Directory.Delete(folder);
            }
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
