using System.Xml.Linq;

namespace LaserEngrave.Machines.Tests;

/// <summary>The projects' references point down only, as docs/architecture.md draws them: the wire's codec needs nothing
/// of ours, Core only the wire, the host and the twin do not know each other, and the front ends reach both through
/// Machines.</summary>
public class ProjectLayoutTests
{
    private static readonly Dictionary<string, string[]> Allowed = new(StringComparer.Ordinal)
    {
        ["LaserEngrave.Wire"] = [],
        ["LaserEngrave.Core"] = ["LaserEngrave.Wire"],
        ["LaserEngrave.Devices"] = ["LaserEngrave.Core", "LaserEngrave.Wire"],
        ["LaserEngrave.Simulator"] = ["LaserEngrave.Core", "LaserEngrave.Wire"],
        ["LaserEngrave.Machines"] = ["LaserEngrave.Devices", "LaserEngrave.Simulator"],
        ["LaserEngrave.App"] = ["LaserEngrave.Core", "LaserEngrave.Machines"],
        ["LaserEngrave.Cli"] = ["LaserEngrave.Core", "LaserEngrave.Machines"],
    };

    [Fact]
    public void EveryProject_ReferencesOnlyTheProjectsBelowIt()
    {
        var src = Path.Combine(RepositoryRoot(), "src");
        var projects = Directory.GetDirectories(src).Select(Path.GetFileName).Order(StringComparer.Ordinal).ToArray();

        Assert.Equal(Allowed.Keys.Order(StringComparer.Ordinal), projects!);
        foreach (var project in projects)
        {
            var references = XDocument.Load(Path.Combine(src, project!, project + ".csproj"))
                .Descendants("ProjectReference")
                .Select(r => Path.GetFileNameWithoutExtension(r.Attribute("Include")!.Value.Replace('\\', '/')))
                .Order(StringComparer.Ordinal);
            Assert.True(references.SequenceEqual(Allowed[project!]), $"{project} references {string.Join(", ", references)}; the layout allows {string.Join(", ", Allowed[project!])}");
        }
    }

    private static string RepositoryRoot()
    {
        for (var folder = new DirectoryInfo(AppContext.BaseDirectory); folder is not null; folder = folder.Parent)
        {
            if (File.Exists(Path.Combine(folder.FullName, "LaserEngrave.sln")))
            {
                return folder.FullName;
            }
        }

        throw new InvalidOperationException($"no LaserEngrave.sln above {AppContext.BaseDirectory}");
    }
}
