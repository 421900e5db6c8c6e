using System.Text.Json;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;

namespace LaserEngrave.Cli.Tests;

public sealed class LogCommandsTests : IDisposable
{
    private readonly string folder = Path.Combine(Path.GetTempPath(), $"le-cli-log-{Guid.NewGuid():N}");

    private static RunRecord Record(string sample, DateTimeOffset start)
    {
        var image = Path.Combine(CliHarness.RepositoryRoot, "assets", "qr-code.bmp");
        var job = PreparedJob.Prepare(new JobSpec { ImagePath = image, Size = SizeSpec.Width(5) });
        return RunRecord.ForJob(job, PreparedJob.HashFile(image), start) with
        {
            Outcome = RunOutcome.Completed,
            SampleId = sample,
            RunsDone = job.Statistics.BurnRuns,
            RowsDone = job.Statistics.Rows,
            ActualSeconds = 12.5,
        };
    }

    [Fact]
    public async Task LogShow_WrittenRun_PrintsTheSummary()
    {
        var files = new RunLogStore(folder).Write(Record("S-1", DateTimeOffset.Now));

        var (exit, output, _) = await CliHarness.RunAsync("log", "show", files.JsonPath);

        Assert.Equal(0, exit);
        Assert.Contains("Sample:             S-1", output, StringComparison.Ordinal);
        Assert.Contains("Outcome:            completed", output, StringComparison.Ordinal);
        Assert.Equal(await File.ReadAllTextAsync(files.TextPath, TestContext.Current.CancellationToken), output);
    }

    [Fact]
    public async Task LogShowJson_WrittenRun_PrintsTheRecord()
    {
        var record = Record("S-2", DateTimeOffset.Now);
        var files = new RunLogStore(folder).Write(record);

        var (exit, output, _) = await CliHarness.RunAsync("log", "show", files.JsonPath, "--json");

        Assert.Equal(0, exit);
        using var json = JsonDocument.Parse(output);
        Assert.Equal("S-2", json.RootElement.GetProperty("sampleId").GetString());
        Assert.Equal(record.Image.Sha256, json.RootElement.GetProperty("image").GetProperty("sha256").GetString());
    }

    [Fact]
    public async Task LogShow_MissingFile_Exit2WithOneLine()
    {
        var path = Path.Combine(folder, "none.json");

        var (exit, _, error) = await CliHarness.RunAsync("log", "show", path);

        Assert.Equal(2, exit);
        Assert.Equal($"laserengrave: {path}: no such run log", error.TrimEnd());
    }

    [Fact]
    public async Task LogShow_NotARunLog_Exit2WithOneLine()
    {
        Directory.CreateDirectory(folder);
        var path = Path.Combine(folder, "bad.json");
        await File.WriteAllTextAsync(path, "{\"hello\": 1}", TestContext.Current.CancellationToken);

        var (exit, _, error) = await CliHarness.RunAsync("log", "show", path);

        Assert.Equal(2, exit);
        Assert.StartsWith($"laserengrave: {path}: not a run log", error, StringComparison.Ordinal);
        Assert.Single(error.TrimEnd().Split('\n'));
    }

    [Fact]
    public async Task LogList_TwoRuns_NewestFirstOneLineEach()
    {
        var store = new RunLogStore(folder);
        var older = store.Write(Record("OLD", DateTimeOffset.Now.AddHours(-2)));
        var newer = store.Write(Record("NEW", DateTimeOffset.Now));

        var (exit, output, _) = await CliHarness.RunAsync("log", "list", "--log-dir", folder);

        Assert.Equal(0, exit);
        var lines = output.TrimEnd().Split('\n');
        Assert.Equal(2, lines.Length);
        Assert.Contains("NEW", lines[0], StringComparison.Ordinal);
        Assert.EndsWith(newer.JsonPath, lines[0], StringComparison.Ordinal);
        Assert.EndsWith(older.JsonPath, lines[1], StringComparison.Ordinal);
        Assert.Contains("completed", lines[1], StringComparison.Ordinal);
    }

    [Fact]
    public async Task LogListCsv_TwoRuns_HeaderThenARowEachNewestFirst()
    {
        var store = new RunLogStore(folder);
        var older = store.Write(Record("OLD", DateTimeOffset.Now.AddHours(-2)));
        var newer = store.Write(Record("NEW", DateTimeOffset.Now));

        var (exit, output, _) = await CliHarness.RunAsync("log", "list", "--log-dir", folder, "--csv");

        Assert.Equal(0, exit);
        var lines = output.TrimEnd().Split("\r\n");
        Assert.Equal(3, lines.Length);
        Assert.StartsWith("started,sample ID,image or drawing,kind,width mm,", lines[0], StringComparison.Ordinal);
        Assert.Contains(",NEW,qr-code.bmp,image,", lines[1], StringComparison.Ordinal);
        Assert.Contains(",completed,12.5,", lines[1], StringComparison.Ordinal);
        Assert.EndsWith(newer.JsonPath, lines[1], StringComparison.Ordinal);
        Assert.EndsWith(older.JsonPath, lines[2], StringComparison.Ordinal);
    }

    [Fact]
    public async Task LogListCsvDecimalComma_Run_SemicolonsAndDecimalCommas()
    {
        new RunLogStore(folder).Write(Record("S-9", DateTimeOffset.Now));

        var (exit, output, _) = await CliHarness.RunAsync("log", "list", folder, "--csv", "--decimal-comma");

        Assert.Equal(0, exit);
        Assert.StartsWith("started;sample ID;", output, StringComparison.Ordinal);
        Assert.Contains(";completed;12,5;", output, StringComparison.Ordinal);
    }

    [Fact]
    public async Task LogListDecimalComma_WithoutCsv_Exit2()
    {
        Directory.CreateDirectory(folder);

        var (exit, _, error) = await CliHarness.RunAsync("log", "list", folder, "--decimal-comma");

        Assert.Equal(2, exit);
        Assert.Contains("--decimal-comma is for the CSV: add --csv", error, StringComparison.Ordinal);
    }

    [Fact]
    public async Task LogList_AFileOrNoFolder_OneLineExit2()
    {
        Directory.CreateDirectory(folder);
        var file = Path.Combine(folder, "a.json");
        await File.WriteAllTextAsync(file, "{}", TestContext.Current.CancellationToken);

        var (fileExit, fileOut, fileError) = await CliHarness.RunAsync("log", "list", file);
        var (dirExit, _, dirError) = await CliHarness.RunAsync("log", "list", "--log-dir", Path.Combine(folder, "missing"));

        Assert.Equal((2, 2), (fileExit, dirExit));
        Assert.Equal($"laserengrave: {file} is a file, not a log folder: `laserengrave log show {file}` shows one run log", fileError.TrimEnd());
        Assert.Equal(string.Empty, fileOut);
        Assert.Contains("no such log folder", dirError, StringComparison.Ordinal);
    }

    [Fact]
    public async Task LogList_EmptyFolder_SaysSo()
    {
        Directory.CreateDirectory(folder);
        var (exit, output, _) = await CliHarness.RunAsync("log", "list", "--log-dir", folder);

        Assert.Equal(0, exit);
        Assert.StartsWith("no run logs in ", output, StringComparison.Ordinal);
    }

    public void Dispose()
    {
        if (Directory.Exists(folder))
        {
            Directory.Delete(folder, recursive: true);
        }
    }
}
