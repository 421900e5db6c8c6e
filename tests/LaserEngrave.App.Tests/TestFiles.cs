using LaserEngrave.Core.Imaging;

namespace LaserEngrave.App.Tests;

/// <summary>Files the tests use: the repository's assets and small images written on the fly.</summary>
internal static class TestFiles
{
    public static string Asset(string name) => Path.Combine(RepositoryRoot(), "assets", name);

    /// <summary>A file of the repository, by its path from the root (docs/openapi.json).</summary>
    public static string RepositoryFile(string path) => Path.Combine(RepositoryRoot(), path);

    private static string RepositoryRoot()
    {
        var folder = new DirectoryInfo(AppContext.BaseDirectory);
        while (folder is not null && !File.Exists(Path.Combine(folder.FullName, "LaserEngrave.sln")))
        {
            folder = folder.Parent;
        }

        return folder?.FullName ?? throw new InvalidOperationException("repository root not found");
    }

    /// <summary>A temporary folder, deleted when disposed.</summary>
    public static TempFolder NewFolder() => new();

    /// <summary>Writes a 1-bit PNG of <paramref name="width"/> x <paramref name="height"/> with a checkerboard of burnt squares.</summary>
    public static string WriteChecker(string folder, int width, int height, int cell = 2)
    {
        var mask = new BitMask(width, height);
        for (var y = 0; y < height; y++)
        {
            for (var x = 0; x < width; x++)
            {
                mask[x, y] = ((x / cell) + (y / cell)) % 2 == 0;
            }
        }

        var path = Path.Combine(folder, $"checker-{width}x{height}.png");
        PngWriter.WriteMask(path, mask);
        return path;
    }

    internal sealed class TempFolder : IDisposable
    {
        public TempFolder()
        {
            Path = System.IO.Path.Combine(System.IO.Path.GetTempPath(), "le-app-tests-" + Guid.NewGuid().ToString("N"));
            Directory.CreateDirectory(Path);
        }

        public string Path { get; }

        public void Dispose()
        {
            try
            {
                Directory.Delete(Path, recursive: true);
            }
            catch (IOException)
            {
                // A file still open by a closing server; the temp folder is cleaned by the system later.
            }
        }
    }
}
