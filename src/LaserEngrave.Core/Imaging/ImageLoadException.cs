namespace LaserEngrave.Core.Imaging;

/// <summary>An image file that cannot be read or decoded; the message is one line naming the file and the problem.</summary>
public sealed class ImageLoadException : Exception
{
    public ImageLoadException(string path, string problem, Exception? innerException = null)
        : base($"{path}: {problem}", innerException)
    {
        Path = path;
        Problem = problem;
    }

    /// <summary>The file as the caller named it.</summary>
    public string Path { get; }

    /// <summary>What is wrong with it, without the path.</summary>
    public string Problem { get; }
}
