namespace LaserEngrave.App.Services;

/// <summary>Files the page hands over and folders the user asks to see.</summary>
public interface IFileAccess
{
    /// <summary>Keeps an uploaded file under the app's image folder; returns its path.</summary>
    Task<string> SaveUploadAsync(string fileName, Stream content, CancellationToken cancellationToken);

    bool Exists(string path);

    /// <summary>The sample images shipped with the app (assets/ of the repository), full paths, by name.</summary>
    IReadOnlyList<string> SampleImages();

    /// <summary>Opens a folder in the system's file manager.</summary>
    void OpenFolder(string path);
}
