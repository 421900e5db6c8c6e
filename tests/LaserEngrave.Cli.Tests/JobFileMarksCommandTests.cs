using System.Text.Json;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Marks;

namespace LaserEngrave.Cli.Tests;

/// <summary>
/// `engrave --job FILE` of a job file with a mark layer beside an image layer: the mark made at load, numbered from the
/// counter, its text and place in the log, the counter advanced only by a completed run, a resume keeping its numbers.
/// </summary>
public sealed class JobFileMarksCommandTests : IDisposable
{
    private readonly string _folder = Directory.CreateTempSubdirectory("le-job-marks-").FullName;

    public void Dispose() => Directory.Delete(_folder, recursive: true);

    private string Counter => Path.Combine(_folder, MarkCounter.FileName);

    private string Logs => Path.Combine(_folder, "logs");

    /// <summary>A small image and a small text mark (0.2 mm high), about 45 s on the twin.</summary>
    private string WriteJob(string mark = """{ "text": "S-{n:000}", "textHeightMm": 0.2, "originMm": [5, 6] }""")
    {
        File.Copy(Path.Combine(CliHarness.RepositoryRoot, "assets", "qr-code.bmp"), Path.Combine(_folder, "qr-code.bmp"), overwrite: true);
        var job = Path.Combine(_folder, "job.json");
        File.WriteAllText(job, $$"""
            { "layers": [
              { "name": "logo", "source": "qr-code.bmp", "widthMm": 0.5, "originMm": [5, 5] },
              { "name": "id", "mark": {{mark}} }
            ] }
            """);
        return job;
    }

    private static RunRecord LogOf(string output)
    {
        using var json = JsonDocument.Parse(output);
        return RunLogStore.Read(json.RootElement.GetProperty("logPath").GetString()!);
    }

    [Fact]
    public async Task Engrave_ImageAndMarkLayers_BurnsTheResolvedTextLogsItAndAdvancesTheCounterOnce()
    {
        var job = WriteJob();

        var (exit, output, error) = await CliHarness.RunAsync("engrave", "--job", job, "--simulate", "--json", "--log-dir", Logs, "--counter", Counter);

        Assert.True(exit == 0, error);
        var record = LogOf(output);
        Assert.Equal(RunOutcome.Completed, record.Outcome);
        Assert.Equal(["logo", "text \"S-001\""], record.Layers!.Select(l => l.Name));
        var text = record.Layers![1];
        Assert.Equal((RunOutcome.Completed, 6.0), (text.Outcome!.Value, text.OriginYMm));
        Assert.InRange(text.OriginXMm, 5, 5.1);
        Assert.Equal((1, 1), (record.JobFile!.Marks!.FirstNumber, record.JobFile.Marks.Count));
        Assert.Equal(2, new MarkCounter(Counter).Next());
        Assert.Contains("the sample counter's next number is 2", error, StringComparison.Ordinal);

        // Repeating that completed run would burn S-001 twice: refused; the job file itself makes the next number.
        var log = Directory.EnumerateFiles(Logs, "*.json").Single();
        var (repeatExit, _, repeatError) = await CliHarness.RunAsync("engrave", "--from-log", log, "--simulate", "--log-dir", Logs);
        Assert.True(repeatExit == 2, repeatError);
        Assert.Contains("burned its marks' numbers 1..1", repeatError, StringComparison.Ordinal);
        Assert.Equal(["logo", "text \"S-002\""], JobFile.Load(job, new JobMarks(Counter, Core.Geometry.MachineProfile.Default, DateTimeOffset.UnixEpoch, null)).Select(l => l.Name));
    }

    [Fact]
    public async Task Engrave_MarkLayerAbortedThenResumed_CounterKeptAndTheResumeBurnsTheNumberItStartedWith()
    {
        var job = WriteJob();
        var (exit, output, error) = await CliHarness.RunAsync(
            "engrave", "--job", job, "--simulate", "--json", "--log-dir", Logs, "--counter", Counter, "--fault", "silent:stage:after=600");
        Assert.True(exit == 1, error);
        var stopped = LogOf(output);
        Assert.Equal([RunOutcome.Completed, RunOutcome.Failed], stopped.Layers!.Select(l => l.Outcome));
        Assert.Equal(1, new MarkCounter(Counter).Next());

        // Meanwhile another batch completed: the counter moved on, but the resumed run keeps the number its log carries.
        new MarkCounter(Counter).Set(5);
        var log = Directory.EnumerateFiles(Logs, "*.json").Single();
        (exit, output, error) = await CliHarness.RunAsync("engrave", "--from-log", log, "--resume", "--simulate", "--json", "--log-dir", Logs);

        Assert.True(exit == 0, error);
        var resumed = LogOf(output);
        Assert.True(resumed.Resumed);
        Assert.Equal(RunOutcome.Completed, resumed.Outcome);
        Assert.Equal("text \"S-001\"", resumed.Layers![1].Name);
        Assert.Equal(1, resumed.JobFile!.Marks!.FirstNumber);
        Assert.Equal(5, new MarkCounter(Counter).Next());
    }

    [Fact]
    public async Task Engrave_MarkLayerAbortedThenResumed_TheResumeAdvancesTheCounterPastIt()
    {
        var job = WriteJob();
        var (exit, _, error) = await CliHarness.RunAsync(
            "engrave", "--job", job, "--simulate", "--log-dir", Logs, "--counter", Counter, "--fault", "silent:stage:after=600");
        Assert.True(exit == 1, error);
        Assert.False(File.Exists(Counter), "an aborted run leaves the counter");

        var log = Directory.EnumerateFiles(Logs, "*.json").Single();
        (exit, _, error) = await CliHarness.RunAsync("engrave", "--from-log", log, "--resume", "--simulate", "--log-dir", Logs);

        Assert.True(exit == 0, error);
        Assert.Equal(2, new MarkCounter(Counter).Next());
    }

    [Fact]
    public async Task Engrave_StoppedRunContinuedToItsEndThenContinuedAgain_RefusedSoNoNumberBurnsTwice()
    {
        var job = WriteJob();
        var (exit, _, error) = await CliHarness.RunAsync(
            "engrave", "--job", job, "--simulate", "--log-dir", Logs, "--counter", Counter, "--fault", "silent:stage:after=600");
        Assert.True(exit == 1, error);
        var log = Directory.EnumerateFiles(Logs, "*.json").Single();
        (exit, _, error) = await CliHarness.RunAsync("engrave", "--from-log", log, "--resume", "--simulate", "--log-dir", Logs);
        Assert.True(exit == 0, error);

        (exit, var output, error) = await CliHarness.RunAsync("engrave", "--from-log", log, "--resume", "--simulate", "--log-dir", Logs);

        Assert.Equal(2, exit);
        Assert.Empty(output);
        Assert.Contains("a completed run burned its marks' numbers 1..1", error, StringComparison.Ordinal);
        Assert.Equal(2, Directory.EnumerateFiles(Logs, "*.json").Count());
        Assert.Equal(2, new MarkCounter(Counter).Next());
    }

    [Theory]
    [InlineData("""{ "text": "S", "colour": "red" }""", "job.json: layer 2 \"id\" (mark): unknown field \"colour\"")]
    [InlineData("""{ "text": "S", "code": "aztec" }""", "job.json: layer 2 \"id\" (mark): code \"aztec\" is not qr, datamatrix or none")]
    [InlineData("""{ "text": "S", "copies": 1.5 }""", "job.json: layer 2 \"id\" (mark): copies 1.5 must be a whole number")]
    [InlineData("""{ "code": "qr" }""", "job.json: layer 2 \"id\" (mark): \"text\" is missing")]
    [InlineData("""{ "text": "S", "code": "datamatrix", "moduleUm": 5 }""", "job.json: layer 2 \"id\" (mark): module 5 µm is smaller than the spot's")]
    [InlineData("""{ "text": "S", "originMm": [59.9, 5] }""", "job.json: layer 2 \"id\" (mark): the mark \"S\" would reach 60.281 mm in X, past the stage's travel 0..60 mm (originMm 59.9, 5): move originMm to at most 59.619 mm in X")]
    [InlineData("""{ "text": "S", "speedMmPerS": 99 }""", "job.json: layer 2 \"id\" (mark): speedMmPerS 99: outside what the stage takes")]
    [InlineData("""{ "text": "{sample}" }""", "job.json: layer 2 \"id\" (mark): \"{sample}\": {sample} needs the run's sample ID (--sample)")]
    public async Task Engrave_BadMarkInAJobFile_OneLineNamingTheFileTheLayerAndTheFieldExitTwo(string mark, string fragment)
    {
        var job = WriteJob(mark);

        var (exit, output, error) = await CliHarness.RunAsync("engrave", "--job", job, "--simulate", "--log-dir", Logs, "--counter", Counter);

        Assert.True(exit == 2, $"exit {exit}: {error}");
        Assert.Single(error.TrimEnd().Split('\n'));
        Assert.Contains(fragment, error, StringComparison.Ordinal);
        Assert.Equal(string.Empty, output);
        Assert.False(Directory.Exists(Logs) && Directory.EnumerateFiles(Logs).Any(), "nothing ran");
        Assert.False(File.Exists(Counter));
    }

    [Fact]
    public async Task Engrave_MarksMakingTooManyLayers_RefusedBeforeAnyFileIsMade()
    {
        var job = WriteJob();
        var marks = string.Join(", ", Enumerable.Range(0, 3).Select(_ => """{ "mark": { "text": "S", "code": "qr", "moduleUm": 50, "copies": 400 } }"""));
        File.WriteAllText(job, $$"""{ "layers": [ {{marks}} ] }""");

        var (exit, _, error) = await CliHarness.RunAsync("engrave", "--job", job, "--simulate", "--log-dir", Logs, "--counter", Counter);

        Assert.True(exit == 2, error);
        Assert.Contains("job.json: its marks would make 2400 layers, more than the 1000 a job may have", error, StringComparison.Ordinal);
        Assert.False(Directory.Exists(MarkManifest.MarksFolder(job)), "no mark was made");
    }

    [Fact]
    public async Task Engrave_FieldBesideTheMark_IsRefusedNamingIt()
    {
        var job = WriteJob();
        File.WriteAllText(job, """{ "layers": [ { "mark": { "text": "S" }, "originMm": [5, 5] } ] }""");

        var (exit, _, error) = await CliHarness.RunAsync("engrave", "--job", job, "--simulate", "--log-dir", Logs, "--counter", Counter);

        Assert.True(exit == 2, error);
        Assert.Contains("job.json: layer 1: \"originMm\" beside \"mark\": a mark layer has only \"mark\"", error, StringComparison.Ordinal);
    }
}
