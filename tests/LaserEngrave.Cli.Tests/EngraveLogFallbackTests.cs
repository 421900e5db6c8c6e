using System.Text.Json;
using LaserEngrave.Cli.Commands;
using LaserEngrave.Core.Logging;

namespace LaserEngrave.Cli.Tests;

/// <summary>
/// Issue 31 finding 6: when the log folder fails during a run (read-only, full, turned into a file), the record that
/// resumes the run is written to the data folder, said in one line first, and printed with --json in any case.
/// </summary>
public sealed class EngraveLogFallbackTests : IDisposable
{
    // What `engrave --json` printed before the record was added: kept in this order, unchanged.
    private static readonly string[] SummaryFields =
    [
        "outcome", "fault", "stoppedAtMove", "simulated", "resumed", "durationSeconds", "wallSeconds", "engravingSeconds",
        "estimatedSeconds", "estimatedEngravingSeconds", "laserOnSeconds", "rowsDone", "rowsTotal", "runsDone", "runsTotal",
        "logPath", "summaryPath", "burnedPath", "dosePath", "simSeed", "pulses", "missingPixels", "extraPixels",
        "laserOnTravelCount", "edges", "dwells", "pulsesPerPixel", "passes", "passesDone", "mode", "pulsesPerDot",
        "pulsesWhileMoving", "pathDeviationUm", "pulseSpacingUm", "expectedSpacingUm", "drawing", "layers", "lateSwitches",
    ];

    private readonly string folder = Path.Combine(Path.GetTempPath(), $"le-cli-logfallback-{Guid.NewGuid():N}");

    public EngraveLogFallbackTests() => Directory.CreateDirectory(folder);

    private static string QrCode => Path.Combine(CliHarness.RepositoryRoot, "assets", "qr-code.bmp");

    private string LogDir => Path.Combine(folder, "logs");

    private string DataFolder => Path.Combine(folder, "data");

    [Theory]
    [InlineData(FailingDisk.Failure.ReadOnly, "Read-only file system")]
    [InlineData(FailingDisk.Failure.Full, "No space left on device")]
    [InlineData(FailingDisk.Failure.BecomesAFile, "cannot write the run log: ")]
    public async Task EngraveSimulate_LogFolderFailsDuringTheRun_LogInTheDataFolderSaidFirstAndItResumes(FailingDisk.Failure failure, string why)
    {
        EngraveCommand.LogSeam.Value = (new FailingDisk(failure, LogDir), DataFolder);

        var (exit, output, error) = await CliHarness.RunAsync(
            "engrave", QrCode, "--width-mm", "5", "--origin-mm", "10,10", "--simulate", "--fault", "silent:stage:after=400", "--json", "--log-dir", LogDir, "--sample", "S-1");

        Assert.Equal(1, exit);
        using var json = JsonDocument.Parse(output);
        var root = json.RootElement;
        var logPath = root.GetProperty("logPath").GetString()!;
        Assert.Equal(DataFolder, Path.GetDirectoryName(logPath));
        var lines = error.TrimEnd().Split('\n');
        var notice = lines.First(l => l.StartsWith("laserengrave: ", StringComparison.Ordinal));
        Assert.StartsWith($"laserengrave: the run log is in {logPath} instead: {LogDir}", notice, StringComparison.Ordinal);
        Assert.Contains(why, notice, StringComparison.Ordinal);
        Assert.Equal("laserengrave: " + root.GetProperty("logNotice").GetString(), notice);
        Assert.Equal([.. SummaryFields, "logNotice", "runLog"], root.EnumerateObject().Select(p => p.Name));
        Assert.Equal(RunRecord.CurrentSchemaVersion, root.GetProperty("runLog").GetProperty("schemaVersion").GetInt32());

        EngraveCommand.LogSeam.Value = null;
        var resumed = await CliHarness.RunAsync("engrave", "--from-log", logPath, "--resume", "--simulate", "--json", "--log-dir", Path.Combine(folder, "later"));

        Assert.True(resumed.Exit == 0, resumed.Err);
        Assert.Contains("\"outcome\": \"completed\"", resumed.Out, StringComparison.Ordinal);
    }

    [Fact]
    public async Task EngraveSimulate_NoFolderTakesTheLog_OneLineFirstAndTheJsonRecordResumes()
    {
        // The log folder, the data folder and the temporary folder all refuse the log.
        EngraveCommand.LogSeam.Value = (new FailingDisk(FailingDisk.Failure.ReadOnly, null), DataFolder);

        var (exit, output, error) = await CliHarness.RunAsync(
            "engrave", QrCode, "--width-mm", "5", "--origin-mm", "10,10", "--simulate", "--fault", "silent:stage:after=400", "--json", "--log-dir", LogDir);

        Assert.Equal(1, exit);
        var lines = error.TrimEnd().Split('\n');
        var first = Array.FindIndex(lines, l => l.StartsWith("laserengrave: ", StringComparison.Ordinal));
        Assert.StartsWith("laserengrave: the run ended (failed) but its log could not be written; the record is in the JSON on stdout (runLog): ", lines[first], StringComparison.Ordinal);
        Assert.Contains("nor in a fallback folder", lines[first], StringComparison.Ordinal);
        Assert.True(first < Array.IndexOf(lines, "LaserEngrave run"), "the line comes before the summary");
        using var json = JsonDocument.Parse(output);
        var root = json.RootElement;
        Assert.Equal(JsonValueKind.Null, root.GetProperty("logPath").ValueKind);
        Assert.Equal("failed", root.GetProperty("runLog").GetProperty("outcome").GetString());

        // The record saved from stdout by hand is a log that resumes the run.
        EngraveCommand.LogSeam.Value = null;
        var saved = Path.Combine(folder, "saved.json");
        await File.WriteAllTextAsync(saved, root.GetProperty("runLog").GetRawText(), TestContext.Current.CancellationToken);
        var resumed = await CliHarness.RunAsync("engrave", "--from-log", saved, "--resume", "--simulate", "--json", "--log-dir", Path.Combine(folder, "later"));

        Assert.True(resumed.Exit == 0, resumed.Err);
        Assert.Contains("\"outcome\": \"completed\"", resumed.Out, StringComparison.Ordinal);
    }

    [Fact]
    public async Task EngraveSimulate_LogWritten_JsonCarriesTheRecordAsTheLogHoldsIt()
    {
        var (exit, output, error) = await CliHarness.RunAsync("engrave", QrCode, "--width-mm", "5", "--origin-mm", "10,10", "--simulate", "--json", "--log-dir", LogDir);

        Assert.True(exit == 0, error);
        using var json = JsonDocument.Parse(output);
        var root = json.RootElement;
        Assert.Equal(JsonValueKind.Null, root.GetProperty("logNotice").ValueKind);
        var logged = RunLogStore.Read(root.GetProperty("logPath").GetString()!);
        Assert.Equal(RunRecordJson.Serialize(logged), RunRecordJson.Serialize(RunRecordJson.Deserialize(root.GetProperty("runLog").GetRawText(), "stdout")));
    }

    public void Dispose()
    {
        EngraveCommand.LogSeam.Value = null;
        Directory.Delete(folder, recursive: true);
    }

    /// <summary>
    /// A log folder that takes the check before the run and fails when the log is written: a read-only mount, a full disk
    /// (acted: as root neither chmod nor a small disk is at hand) or, for real, a file put where the folder was.
    /// </summary>
    /// <param name="failure">How it fails.</param>
    /// <param name="logFolder">The folder that fails; null: every folder.</param>
    public sealed class FailingDisk(FailingDisk.Failure failure, string? logFolder) : RunLogFileSystem
    {
        public enum Failure
        {
            ReadOnly,
            Full,
            BecomesAFile,
        }

        public override Stream CreateNew(string path)
        {
            var folder = Path.GetDirectoryName(path)!;
            if (Path.GetFileName(path).StartsWith(".write-check-", StringComparison.Ordinal) || (logFolder is not null && folder != logFolder))
            {
                return base.CreateNew(path);
            }

            switch (failure)
            {
                case Failure.ReadOnly:
                    throw new IOException("Read-only file system");
                case Failure.Full:
                    throw new IOException("No space left on device");
                default:
                    Directory.Delete(folder, recursive: true);
                    File.WriteAllText(folder, "a file where the log folder was");
                    return base.CreateNew(path);
            }
        }
    }
}
