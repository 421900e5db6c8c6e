namespace LaserEngrave.Cli.Tests;

/// <summary>Runs `laserengrave` in-process and captures what it prints.</summary>
internal static class CliHarness
{
    public static async Task<(int Exit, string Out, string Err)> RunAsync(params string[] args)
    {
        using var stdout = new StringWriter();
        using var stderr = new StringWriter();
        var exit = await CliRunner.InvokeAsync(Program.BuildRoot(), args, stdout, stderr, TestContext.Current.CancellationToken);
        return (exit, stdout.ToString(), stderr.ToString());
    }

    /// <summary>The repository root (the folder holding LaserEngrave.sln).</summary>
    public static string RepositoryRoot
    {
        get
        {
            var dir = new DirectoryInfo(AppContext.BaseDirectory);
            while (dir is not null && !File.Exists(Path.Combine(dir.FullName, "LaserEngrave.sln")))
            {
                dir = dir.Parent;
            }

            return dir?.FullName ?? throw new InvalidOperationException($"LaserEngrave.sln not found above {AppContext.BaseDirectory}");
        }
    }

    public static string BmpSuite(string file)
    {
        var path = Path.GetFullPath(Path.Combine(RepositoryRoot, "..", "shared", "bmpsuite", file));
        return File.Exists(path) ? path : throw new FileNotFoundException($"BMP suite file missing: {path} (shared/ must sit beside the repository)");
    }

    public static string TempFile(string extension) => Path.Combine(Path.GetTempPath(), $"le-cli-{Guid.NewGuid():N}{extension}");
}
