using System.Reflection;
using System.Text.RegularExpressions;
using LaserEngrave.Core.Jobs;

namespace LaserEngrave.Core.Tests;

/// <summary>
/// Core's folders as layers (issue 35): which folder's source uses a type of which other folder, read from the source
/// (a type of folder G counts where a file imports G's namespace or writes G.Type), and no two folders that use each
/// other, directly or round a longer loop.
/// </summary>
public partial class FolderGraphTests
{
    [Fact]
    public void FolderGraph_CoreSource_HasNoCycle()
    {
        var graph = Graph();
        var whole = Describe(graph);
        var cycles = Cycles(graph).Select(c => string.Join(" -> ", c.Order(StringComparer.Ordinal))).ToList();

        Assert.True(cycles.Count == 0, "Core's folders that use each other: " + string.Join("; ", cycles) + "\n" + whole);
    }

    [Fact]
    public void FolderGraph_CoreSource_FindsTheObviousEdges()
    {
        // The reader itself: Jobs plans images (Imaging, Planning), reads a drawing's name (Vectors.DrawingReader, written
        // with its folder), and Input (number text) is a leaf that uses no other folder.
        var graph = Graph();

        Assert.Contains("Planning", graph["Jobs"]);
        Assert.Contains("Imaging", graph["Jobs"]);
        Assert.Contains("Vectors", graph["Jobs"]);
        Assert.Empty(graph["Input"]);
    }

    [Fact]
    public void Cycles_TwoFoldersRoundAThird_FoundAsOne()
    {
        var graph = new Dictionary<string, HashSet<string>>
        {
            ["A"] = ["B"],
            ["B"] = ["C"],
            ["C"] = ["A"],
            ["D"] = ["A"],
        };

        var cycle = Assert.Single(Cycles(graph));

        Assert.Equal(["A", "B", "C"], cycle.Order(StringComparer.Ordinal));
    }

    /// <summary>Folder to the folders whose types its source uses.</summary>
    private static Dictionary<string, HashSet<string>> Graph()
    {
        var core = typeof(EngraveJob).Assembly;
        var typesByFolder = core.GetTypes()
            .Where(t => !t.IsNested && Folder(t.Namespace) is not null && !t.Name.Contains('<', StringComparison.Ordinal))
            .GroupBy(t => Folder(t.Namespace)!)
            .ToDictionary(g => g.Key, g => g.Select(t => t.Name.Split('`')[0]).ToHashSet(StringComparer.Ordinal));
        var folderOfType = new Dictionary<string, HashSet<string>>(StringComparer.Ordinal);
        foreach (var (folder, names) in typesByFolder)
        {
            foreach (var name in names)
            {
                if (!folderOfType.TryGetValue(name, out var folders))
                {
                    folderOfType[name] = folders = [];
                }

                folders.Add(folder);
            }
        }

        var root = Path.Combine(RepositoryRoot(), "src", "LaserEngrave.Core");
        var graph = typesByFolder.Keys.ToDictionary(f => f, _ => new HashSet<string>(StringComparer.Ordinal));
        foreach (var file in Directory.EnumerateFiles(root, "*.cs", SearchOption.AllDirectories))
        {
            var relative = Path.GetRelativePath(root, file).Split(Path.DirectorySeparatorChar);
            if (relative.Length < 2 || relative[0] is "bin" or "obj" || !graph.TryGetValue(relative[0], out var uses))
            {
                continue;
            }

            var source = Comments().Replace(File.ReadAllText(file), " ");
            var imported = Imports().Matches(source).Select(m => m.Groups["folder"].Value).ToHashSet(StringComparer.Ordinal);
            var own = typesByFolder[relative[0]];
            foreach (Match token in Identifiers().Matches(source))
            {
                var name = token.Groups["name"].Value;
                if (own.Contains(name) || !folderOfType.TryGetValue(name, out var folders))
                {
                    continue;
                }

                // Imported by its namespace, or written with it (Vectors.DrawingReader, Core.Imaging.BitMask).
                var qualifier = Qualifier(source, token.Index);
                foreach (var folder in folders.Where(f => f != relative[0] && (imported.Contains(f) || qualifier == f)))
                {
                    uses.Add(folder);
                }
            }

            // A static import or an alias names the type's namespace itself.
            foreach (Match alias in TypeImports().Matches(source))
            {
                if (alias.Groups["folder"].Value is var folder && folder != relative[0] && graph.ContainsKey(folder))
                {
                    uses.Add(folder);
                }
            }
        }

        return graph;
    }

    /// <summary>The strongly connected components with more than one folder (Tarjan's algorithm).</summary>
    private static List<List<string>> Cycles(Dictionary<string, HashSet<string>> graph)
    {
        var index = new Dictionary<string, int>();
        var low = new Dictionary<string, int>();
        var stack = new Stack<string>();
        var onStack = new HashSet<string>();
        var found = new List<List<string>>();

        void Visit(string v)
        {
            index[v] = low[v] = index.Count;
            stack.Push(v);
            onStack.Add(v);
            foreach (var w in graph.GetValueOrDefault(v) ?? [])
            {
                if (!index.ContainsKey(w))
                {
                    Visit(w);
                    low[v] = Math.Min(low[v], low[w]);
                }
                else if (onStack.Contains(w))
                {
                    low[v] = Math.Min(low[v], index[w]);
                }
            }

            if (low[v] == index[v])
            {
                var component = new List<string>();
                string w;
                do
                {
                    w = stack.Pop();
                    onStack.Remove(w);
                    component.Add(w);
                }
                while (w != v);
                if (component.Count > 1)
                {
                    found.Add(component);
                }
            }
        }

        foreach (var v in graph.Keys.Order(StringComparer.Ordinal))
        {
            if (!index.ContainsKey(v))
            {
                Visit(v);
            }
        }

        return found;
    }

    private static string Describe(Dictionary<string, HashSet<string>> graph) =>
        string.Join("\n", graph.OrderBy(p => p.Key, StringComparer.Ordinal).Select(p => $"{p.Key}: {string.Join(" ", p.Value.Order(StringComparer.Ordinal))}"));

    // LaserEngrave.Core.Jobs and LaserEngrave.Core.Marks.Fonts are the folders Jobs and Marks; LaserEngrave.Core itself none.
    private static string? Folder(string? ns) =>
        ns is not null && ns.StartsWith("LaserEngrave.Core.", StringComparison.Ordinal) ? ns["LaserEngrave.Core.".Length..].Split('.')[0] : null;

    // The word before ".Name" at `at` (Vectors in Vectors.DrawingReader); empty when the name stands alone.
    private static string Qualifier(string source, int at)
    {
        var end = at;
        while (end > 0 && char.IsWhiteSpace(source[end - 1]))
        {
            end--;
        }

        if (end == 0 || source[end - 1] != '.')
        {
            return string.Empty;
        }

        end--;
        while (end > 0 && char.IsWhiteSpace(source[end - 1]))
        {
            end--;
        }

        var start = end;
        while (start > 0 && (char.IsLetterOrDigit(source[start - 1]) || source[start - 1] == '_'))
        {
            start--;
        }

        return source[start..end];
    }

    private static string RepositoryRoot()
    {
        var folder = new DirectoryInfo(AppContext.BaseDirectory);
        while (folder is not null && !File.Exists(Path.Combine(folder.FullName, "LaserEngrave.sln")))
        {
            folder = folder.Parent;
        }

        Assert.NotNull(folder);
        return folder.FullName;
    }

    [GeneratedRegex(@"//[^\n]*|/\*.*?\*/", RegexOptions.Singleline)]
    private static partial Regex Comments();

    [GeneratedRegex(@"^\s*(global\s+)?using\s+LaserEngrave\.Core\.(?<folder>\w+)(\.\w+)*\s*;", RegexOptions.Multiline)]
    private static partial Regex Imports();

    [GeneratedRegex(@"^\s*(global\s+)?using\s+(static\s+|\w+\s*=\s*)LaserEngrave\.Core\.(?<folder>\w+)", RegexOptions.Multiline)]
    private static partial Regex TypeImports();

    [GeneratedRegex(@"\b(?<name>[A-Z]\w*)\b")]
    private static partial Regex Identifiers();
}
