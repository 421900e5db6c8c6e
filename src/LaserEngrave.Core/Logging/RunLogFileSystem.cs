namespace LaserEngrave.Core.Logging;

/// <summary>The few file operations a <see cref="RunLogStore"/> writes with; tests replace it to act a full or read-only disk.</summary>
public class RunLogFileSystem
{
    /// <summary>The real file system.</summary>
    public static RunLogFileSystem Real { get; } = new();

    /// <summary>Creates a new file for writing; throws <see cref="IOException"/> when it exists or cannot be created.</summary>
    public virtual Stream CreateNew(string path) => new FileStream(path, FileMode.CreateNew, FileAccess.Write, FileShare.None);

    /// <summary>Gives a complete file its name, never replacing a file of that name (an <see cref="IOException"/> then).</summary>
    public virtual void Move(string from, string to) => File.Move(from, to, overwrite: false);

    public virtual bool Exists(string path) => File.Exists(path);

    public virtual void Delete(string path) => File.Delete(path);

    /// <summary>Free bytes on the folder's drive for this user; null when the platform cannot say.</summary>
    public virtual long? AvailableBytes(string folder)
    {
        try
        {
            return new DriveInfo(folder).AvailableFreeSpace;
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException or ArgumentException)
        {
            return null;
        }
    }
}
