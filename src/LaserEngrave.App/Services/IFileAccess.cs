namespace LaserEngrave.App.Services;

/// <summary>Files the page hands over and folders the user asks to see.</summary>
public interface IFileAccess
{
    /// <summary>The largest upload the app takes, bytes (512 MB); the web server's and the form's limits are set to it.</summary>
    const long MaxUploadBytes = 512L << 20;

    /// <summary>The longest upload name taken, characters: with the temporary name's prefix and suffix it stays within a file system's 255 bytes.</summary>
    const int MaxUploadNameLength = 200;

    /// <summary>The most the image folder holds, all uploads together (4 GB): an upload past it is refused, nothing is removed by itself.</summary>
    const long UploadQuotaBytes = 4L << 30;

    /// <summary>
    /// Keeps an uploaded file under the app's image folder, in a folder named after its content (never replacing another
    /// upload); returns its path. <paramref name="beforeCommit"/> runs once the bytes are whole, before the file is put in
    /// place: what it throws (the run interlock's refusal) leaves nothing behind.
    /// </summary>
    /// <exception cref="UploadException">A name that cannot be a file's on Linux, macOS or Windows (a path, a control or invisible formatting character, a device name such as CON or aux.bmp, a trailing dot or space, "." or "..", longer than <see cref="MaxUploadNameLength"/>), too large, past the quota, interrupted or not writable: one line naming the file; nothing is left behind.</exception>
    Task<string> SaveUploadAsync(string fileName, Stream content, CancellationToken cancellationToken, Action? beforeCommit = null);

    bool Exists(string path);

    /// <summary>Removes an upload the app could not open (it did not decode), so images/ keeps only files that open; any other path is left alone.</summary>
    void RemoveUpload(string path);

    /// <summary>The sample images shipped with the app (assets/ of the repository), full paths, by name.</summary>
    IReadOnlyList<string> SampleImages();

    /// <summary>Writes a generated test pattern (black = burn) as a PNG under the app's image folder; returns its path.</summary>
    /// <exception cref="IOException">The folder cannot be written.</exception>
    string SavePattern(string name, Core.Imaging.BitMask mask);

    /// <summary>Opens a folder in the system's file manager.</summary>
    /// <returns>False when nothing can show it (no desktop session to show a window in).</returns>
    /// <exception cref="System.ComponentModel.Win32Exception">The system has nothing to open folders with.</exception>
    bool OpenFolder(string path);
}
