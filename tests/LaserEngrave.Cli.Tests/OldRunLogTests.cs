using System.Text.Json;
using System.Text.Json.Nodes;
using LaserEngrave.Core.Logging;

namespace LaserEngrave.Cli.Tests;

/// <summary>
/// Issue 31 finding 7: every log this program ever wrote can be repeated and resumed. The fixtures are genuine logs,
/// written by the program as it was at each commit named in their file names (Fixtures/RunLogs/README.md).
/// </summary>
public sealed class OldRunLogTests : IDisposable
{
    private readonly string folder = Path.Combine(Path.GetTempPath(), $"le-cli-oldlog-{Guid.NewGuid():N}");

    public OldRunLogTests() => Directory.CreateDirectory(folder);

    public static string FixtureFolder => Path.Combine(CliHarness.RepositoryRoot, "tests", "LaserEngrave.Cli.Tests", "Fixtures", "RunLogs");

    public static TheoryData<string> CompletedLogs => [.. Fixtures("-completed.json")];

    public static TheoryData<string> FailedLogs => [.. Fixtures("-failed.json")];

    private string LogDir => Path.Combine(folder, "logs");

    [Fact]
    public void Fixtures_EverySchemaVersion_HasACompletedAndAFailedLog()
    {
        var versions = Directory.GetFiles(FixtureFolder, "*.json").Select(f => Path.GetFileName(f).Split('-')[0]).Distinct().Order().ToList();

        Assert.Equal(Enumerable.Range(1, RunRecord.CurrentSchemaVersion).Select(v => $"v{v}"), versions);
        foreach (var version in versions)
        {
            Assert.Contains(CompletedLogs, f => Path.GetFileName(f.Data).StartsWith(version + "-", StringComparison.Ordinal));
            Assert.Contains(FailedLogs, f => Path.GetFileName(f.Data).StartsWith(version + "-", StringComparison.Ordinal));
        }
    }

    [Theory]
    [MemberData(nameof(CompletedLogs))]
    public async Task EngraveFromLog_LogOfEveryVersion_RepeatsTheRunToCompletion(string fixture)
    {
        var log = Copy(fixture);

        var (exit, output, error) = await CliHarness.RunAsync("engrave", "--from-log", log, "--simulate", "--json", "--log-dir", LogDir);

        Assert.True(exit == 0, error);
        using var json = JsonDocument.Parse(output);
        var root = json.RootElement;
        Assert.Equal("completed", root.GetProperty("outcome").GetString());
        Assert.Equal((0L, 0L, 0L), (root.GetProperty("missingPixels").GetInt64(), root.GetProperty("extraPixels").GetInt64(), root.GetProperty("laserOnTravelCount").GetInt64()));
        var repeated = RunLogStore.Read(root.GetProperty("logPath").GetString()!);
        var original = JsonNode.Parse(await File.ReadAllTextAsync(log, TestContext.Current.CancellationToken))!;
        Assert.Equal((RunRecord.CurrentSchemaVersion, Path.GetFullPath(log)), (repeated.SchemaVersion, repeated.RepeatOf));
        Assert.Equal(original["process"]!["burnSpeedMmPerS"]!.GetValue<double>(), repeated.Process.BurnSpeedMmPerS);
        Assert.Equal(original["geometry"]!["pitchUm"]!.GetValue<double>(), repeated.Geometry.PitchUm);
    }

    [Theory]
    [MemberData(nameof(FailedLogs))]
    public async Task EngraveResume_FailedLogOfEveryVersion_ResumesToCompletionOnTheTwin(string fixture)
    {
        var log = Copy(fixture);
        var stopped = RunLogStore.Read(log);

        var (exit, output, error) = await CliHarness.RunAsync("engrave", "--from-log", log, "--resume", "--simulate", "--json", "--log-dir", LogDir);

        Assert.True(exit == 0, error);
        using var json = JsonDocument.Parse(output);
        var root = json.RootElement;
        Assert.Equal("completed", root.GetProperty("outcome").GetString());
        Assert.True(root.GetProperty("resumed").GetBoolean());
        Assert.Equal(stopped.RunsTotal, root.GetProperty("runsDone").GetInt64());
        // Checked against what the stopped run had still to burn: nothing missing, nothing extra, nothing on white.
        Assert.Equal((0L, 0L, 0L), (root.GetProperty("missingPixels").GetInt64(), root.GetProperty("extraPixels").GetInt64(), root.GetProperty("laserOnTravelCount").GetInt64()));
    }

    [Fact]
    public async Task EngraveFromLog_FirstLogEverWrittenWithoutStopPoint_RepeatsAndRefusesToResumeInOneLine()
    {
        // The first engrave (c3e32dd) failed every run before it moved, and logged no stop point.
        var log = Copy(Path.Combine(FixtureFolder, "v1-2026-11-23-c3e32dd-first.json"));

        var repeat = await CliHarness.RunAsync("engrave", "--from-log", log, "--simulate", "--json", "--log-dir", LogDir);
        var resume = await CliHarness.RunAsync("engrave", "--from-log", log, "--resume", "--simulate", "--log-dir", LogDir);

        Assert.True(repeat.Exit == 0, repeat.Err);
        Assert.Equal(2, resume.Exit);
        Assert.Contains("no stop point", Assert.Single(resume.Err.TrimEnd().Split('\n')), StringComparison.Ordinal);
    }

    public void Dispose() => Directory.Delete(folder, recursive: true);

    private static IEnumerable<string> Fixtures(string suffix) =>
        Directory.GetFiles(FixtureFolder, "*" + suffix).Order(StringComparer.Ordinal);

    // The fixture as the user has it: its image where the log says, here the repository's copy of the same file (same SHA-256).
    private string Copy(string fixture)
    {
        var node = JsonNode.Parse(File.ReadAllText(fixture))!;
        node["image"]!["path"] = Path.Combine(CliHarness.RepositoryRoot, "assets", "qr-code.bmp");
        var path = Path.Combine(folder, Path.GetFileName(fixture));
        File.WriteAllText(path, node.ToJsonString(new JsonSerializerOptions { WriteIndented = true }));
        return path;
    }
}
