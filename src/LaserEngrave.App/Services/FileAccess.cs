namespace LaserEngrave.App.Services;

/// <summary>The real <see cref="IFileAccess"/>: uploads under <see cref="AppFolders.UploadFolder"/>, folders opened by the shell.</summary>
public sealed class FileAccess(AppFolders folders) : IFileAccess
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

        Directory.CreateDirectory(folders.UploadFolder);
        var path = Path.Combine(folders.UploadFolder, name);
        var file = File.Create(path);
        await using (file.ConfigureAwait(false))
        {
            await content.CopyToAsync(file, cancellationToken).ConfigureAwait(false);
        }

        return path;
    }

    public bool Exists(string path) => File.Exists(path);

    public IReadOnlyList<string> SampleImages() =>
        Directory.Exists(folders.SamplesFolder)
            ? [.. Directory.EnumerateFiles(folders.SamplesFolder).Order(StringComparer.OrdinalIgnoreCase)]
            : [];

    public void OpenFolder(string path)
    {
        Directory.CreateDirectory(path);
        SystemShell.Open(path);
    }
}
