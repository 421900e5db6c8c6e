using System.Text.RegularExpressions;

namespace LaserEngrave.Core.Tests.Imaging;

/// <summary>Finds Jason Summers' BMP suite beside the repository and reads which reference picture belongs to which file.</summary>
internal static partial class BmpSuite
{
    /// <summary>Set to the suite's folder to override the search.</summary>
    public const string EnvironmentVariable = "LASERENGRAVE_BMPSUITE";

    private static readonly Lazy<string?> Location = new(Find);

    /// <summary>The suite's folder; throws with a clear message when it cannot be found, so the tests fail rather than skip.</summary>
    public static string Root => Location.Value ?? throw new InvalidOperationException(
        $"the BMP suite was not found: expected shared/bmpsuite beside the repository (../shared/bmpsuite from the folder holding LaserEngrave.sln, or in a folder above it), or a folder named by {EnvironmentVariable}; searched up from {AppContext.BaseDirectory}");

    /// <summary>Files of one folder (g, q or b) as "g/name.bmp"; a single "missing" entry when the suite is absent, which then fails.</summary>
    public static TheoryData<string> Files(string folder)
    {
        var data = new TheoryData<string>();
        if (Location.Value is null)
        {
            data.Add($"{folder}/(bmpsuite missing)");
            return data;
        }

        foreach (var file in Directory.GetFiles(Path.Combine(Location.Value, folder), "*.bmp").Order(StringComparer.Ordinal))
        {
            data.Add($"{folder}/{Path.GetFileName(file)}");
        }

        return data;
    }

    public static string PathOf(string relative) => Path.Combine(Root, relative);

    /// <summary>The reference renderings html/bmpsuite.html shows for a file (several when viewers may differ), as paths.</summary>
    public static IReadOnlyList<string> References(string relative)
    {
        var html = File.ReadAllText(Path.Combine(Root, "html", "bmpsuite.html"));
        foreach (Match row in RowPattern().Matches(html))
        {
            var cells = row.Groups[1].Value;
            if (!cells.Contains($"<img src=\"../{relative}\">", StringComparison.Ordinal))
            {
                continue;
            }

            return [.. ImagePattern().Matches(cells)
                .Select(m => m.Groups[1].Value)
                .Where(src => !src.StartsWith("../", StringComparison.Ordinal))
                .Select(src => Path.Combine(Root, "html", src))];
        }

        return [];
    }

    private static string? Find()
    {
        var overridden = Environment.GetEnvironmentVariable(EnvironmentVariable);
        if (!string.IsNullOrEmpty(overridden))
        {
            return Directory.Exists(overridden) ? overridden : null;
        }

        var repository = new DirectoryInfo(AppContext.BaseDirectory);
        while (repository is not null && !File.Exists(Path.Combine(repository.FullName, "LaserEngrave.sln")))
        {
            repository = repository.Parent;
        }

        // CI keeps it at ../shared/bmpsuite from the repository; a git worktree sits one level deeper, so look further up too.
        for (var folder = repository?.Parent; folder is not null; folder = folder.Parent)
        {
            var candidate = Path.Combine(folder.FullName, "shared", "bmpsuite");
            if (Directory.Exists(Path.Combine(candidate, "g")))
            {
                return candidate;
            }
        }

        return null;
    }

    [GeneratedRegex(@"<tr>(.*?)</tr>", RegexOptions.Singleline)]
    private static partial Regex RowPattern();

    [GeneratedRegex("<img[^>]*src=\"([^\"]+)\"")]
    private static partial Regex ImagePattern();
}
