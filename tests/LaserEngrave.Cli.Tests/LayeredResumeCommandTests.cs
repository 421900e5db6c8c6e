using System.Text.Json;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;

namespace LaserEngrave.Cli.Tests;

/// <summary>`engrave --from-log LOG [--resume]` of a run of layers: continued from the layer and pass that stopped, refused when anything changed.</summary>
public sealed class LayeredResumeCommandTests : IDisposable
{
    private readonly string _folder = Path.Combine(Path.GetTempPath(), $"le-cli-layers-resume-{Guid.NewGuid():N}");

    public LayeredResumeCommandTests() => Directory.CreateDirectory(_folder);

    private string Logs => Path.Combine(_folder, "logs");

    public void Dispose() => Directory.Delete(_folder, recursive: true);

    /// <summary>A job of three small layers whose sources are copies in the test's folder (so a test may change one).</summary>
    private string WriteJob()
    {
        foreach (var (from, to) in new[] { ("drawings/layers.svg", "layers.svg"), ("qr-code.bmp", "qr-code.bmp") })
        {
            File.Copy(Path.Combine(CliHarness.RepositoryRoot, "assets", from), Path.Combine(_folder, to), overwrite: true);
        }

        var job = Path.Combine(_folder, "job.json");
        File.WriteAllText(job, """
            { "layers": [
              { "name": "marks", "source": "layers.svg", "drawingLayer": "mark", "originMm": [10, 10], "widthMm": 6 },
              { "name": "logo", "source": "qr-code.bmp", "widthMm": 1.5, "originMm": [24, 22] },
              { "name": "cut", "source": "layers.svg", "drawingLayer": "cut", "originMm": [10, 10], "widthMm": 6, "passes": 2 }
            ] }
            """);
        return job;
    }

    /// <summary>Runs the job with the stage going silent in the second layer (the 600th command); returns the log.</summary>
    private async Task<string> StoppedInLayerTwoAsync(string job)
    {
        var (exit, output, error) = await CliHarness.RunAsync("engrave", "--job", job, "--simulate", "--json", "--log-dir", Logs, "--fault", "silent:stage:after=600");
        Assert.True(exit == 1, error);
        using var json = JsonDocument.Parse(output);
        var log = json.RootElement.GetProperty("logPath").GetString()!;
        var record = RunLogStore.Read(log);
        Assert.Equal([RunOutcome.Completed, RunOutcome.Failed, null], record.Layers!.Select(l => l.Outcome));
        Assert.Equal(Path.GetFullPath(job), record.JobFile!.Path);
        return log;
    }

    [Fact]
    public async Task Resume_StoppedInLayerTwo_LayersTwoToThreeCompleteAndLayerOneIsNotBurnedAgain()
    {
        var log = await StoppedInLayerTwoAsync(WriteJob());

        var (exit, output, error) = await CliHarness.RunAsync("engrave", "--from-log", log, "--resume", "--simulate", "--json", "--log-dir", Logs);

        Assert.True(exit == 0, error);
        using var json = JsonDocument.Parse(output);
        var record = RunLogStore.Read(json.RootElement.GetProperty("logPath").GetString()!);
        Assert.True(record.Resumed);
        Assert.Equal(Path.GetFullPath(log), record.RepeatOf);
        Assert.Equal(RunOutcome.Completed, record.Outcome);
        Assert.Equal(3, record.Passes);
        var layers = record.Layers!;
        Assert.All(layers, l => Assert.Equal((RunOutcome.Completed, l.Passes), (l.Outcome!.Value, l.PassesDone)));
        Assert.Equal((0.0, 0.0, true), (layers[0].EngravingSeconds, layers[0].LaserOnSeconds, layers[0].CompletedBefore));
        Assert.False(layers[1].CompletedBefore);
        Assert.Null(layers[0].Simulation);
        Assert.True(layers[1].LaserOnSeconds > 0);

        // The logo goes on from its stop point: what the stopped run burned is not on this fresh twin and is not counted
        // missing (issue 23), and nothing else is missing.
        var stopped = RunLogStore.Read(log);
        var burnedBefore = stopped.Layers![1].Simulation!;
        Assert.Equal(0, layers[1].Simulation!.MissingPixels);
        Assert.Equal(0, layers[1].Simulation!.ExtraPixels);
        Assert.True(layers[2].Simulation!.Path!.DeviationUm.Max <= 3);
        Assert.True(burnedBefore.MissingPixels > 0);
    }

    [Fact]
    public async Task Resume_JobFileChanged_Exit2OneLineAndNothingRuns()
    {
        var job = WriteJob();
        var log = await StoppedInLayerTwoAsync(job);
        File.AppendAllText(job, "\n");
        var before = Directory.GetFiles(Logs).Length;

        var (exit, _, error) = await CliHarness.RunAsync("engrave", "--from-log", log, "--resume", "--simulate", "--log-dir", Logs);

        Assert.Equal(2, exit);
        Assert.Equal($"laserengrave: {Path.GetFullPath(job)}: the job file has changed since the run", error.Trim()[..(error.Trim().IndexOf(" (SHA-256", StringComparison.Ordinal))]);
        Assert.Single(error.TrimEnd().Split('\n'));
        Assert.Equal(before, Directory.GetFiles(Logs).Length);
    }

    [Fact]
    public async Task Resume_LayerSourceChanged_Exit2OneLineNamingTheLayer()
    {
        var log = await StoppedInLayerTwoAsync(WriteJob());
        File.AppendAllText(Path.Combine(_folder, "layers.svg"), "<!-- edited -->\n");

        var (exit, _, error) = await CliHarness.RunAsync("engrave", "--from-log", log, "--resume", "--simulate", "--log-dir", Logs);

        Assert.Equal(2, exit);
        Assert.Contains("the layer \"marks\" source has changed since the run", error, StringComparison.Ordinal);
        Assert.Single(error.TrimEnd().Split('\n'));
    }

    [Fact]
    public async Task Resume_EveryLayerCompleted_Exit2NothingToResume()
    {
        var job = WriteJob();
        var (_, output, _) = await CliHarness.RunAsync("engrave", "--job", job, "--simulate", "--json", "--log-dir", Logs);
        using var json = JsonDocument.Parse(output);

        var (exit, _, error) = await CliHarness.RunAsync("engrave", "--from-log", json.RootElement.GetProperty("logPath").GetString()!, "--resume", "--simulate", "--log-dir", Logs);

        Assert.Equal(2, exit);
        Assert.Contains("every layer of the run completed", error, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("--passes", "2", "--passes with --from-log of a job of layers: each layer has its own passes")]
    [InlineData("--speed-mm-s", "2", "--speed-mm-s with --from-log")]
    public async Task FromLog_LayersWithTheJobsOwnOptions_Exit2OneLine(string option, string value, string expected)
    {
        var log = await StoppedInLayerTwoAsync(WriteJob());

        var (exit, _, error) = await CliHarness.RunAsync("engrave", "--from-log", log, "--resume", "--simulate", option, value);

        Assert.Equal(2, exit);
        Assert.Contains(expected, error, StringComparison.Ordinal);
        Assert.Single(error.TrimEnd().Split('\n'));
    }
}
