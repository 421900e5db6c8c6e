using System.Text.Json;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Logging;

namespace LaserEngrave.Cli.Tests;

/// <summary>`--accept-no-watchdog`: a gate without a watchdog fires only once the person has accepted what then protects the laser.</summary>
public sealed class FrequencyOnlyGateCommandTests : IDisposable
{
    private readonly string folder = Path.Combine(Path.GetTempPath(), $"le-cli-freqgate-{Guid.NewGuid():N}");

    public FrequencyOnlyGateCommandTests() => Directory.CreateDirectory(folder);

    private static string QrCode => Path.Combine(CliHarness.RepositoryRoot, "assets", "qr-code.bmp");

    private static string FrequencyOnly => Path.Combine(CliHarness.RepositoryRoot, "assets", "profiles", "frequency-only.json");

    private string LogDir => Path.Combine(folder, "logs");

    [Theory]
    [InlineData("engrave")]
    [InlineData("fire")]
    [InlineData("laser")]
    public async Task Command_FrequencyOnlyProfileWithoutAcceptance_Exit2WithTheSentenceNothingOpened(string verb)
    {
        string[] args = verb switch
        {
            "engrave" => ["engrave", QrCode, "--width-mm", "5", "--origin-mm", "10,10", "--profile", FrequencyOnly, "--simulate", "--log-dir", LogDir],
            "fire" => ["fire", "--pulses", "10", "--profile", FrequencyOnly, "--simulate"],

            // A port that does not exist: refused before it is opened, or the error would name the port instead.
            _ => ["laser", "on", "1000", "--seconds", "1", "--port", "/dev/le-no-such-port", "--profile", FrequencyOnly],
        };

        var (exit, _, error) = await CliHarness.RunAsync(args);

        Assert.Equal(2, exit);
        var line = Assert.Single(error.Split('\n', StringSplitOptions.RemoveEmptyEntries), l => l.StartsWith("laserengrave: ", StringComparison.Ordinal));
        Assert.Contains(LaserGateProfile.NoWatchdogSentence, line, StringComparison.Ordinal);
        Assert.EndsWith("give --accept-no-watchdog to accept it", line.TrimEnd(), StringComparison.Ordinal);
        Assert.False(Directory.Exists(LogDir) && Directory.EnumerateFiles(LogDir).Any());
    }

    [Fact]
    public async Task EngraveSimulate_FrequencyOnlyProfileAccepted_CompletesNoPulseOnWhiteAndTheLogKeepsTheAcceptance()
    {
        // The front ends' late host, but no stalled write: a frequency-only gate fires until a stalled switch-off arrives
        // (docs/execution.md, "A frequency-only gate").
        Directory.CreateDirectory(folder);
        var options = Path.Combine(folder, "no-stalls.json");
        await File.WriteAllTextAsync(options, """{ "hostLateness": { "typicalMs": 0.5, "tailProbability": 0.01, "tailMs": 5, "lateReadProbability": 0.0005, "lateReadMs": 60 } }""", TestContext.Current.CancellationToken);
        var (exit, output, error) = await CliHarness.RunAsync(
            "engrave", QrCode, "--width-mm", "5", "--origin-mm", "10,10", "--profile", FrequencyOnly, "--accept-no-watchdog", "--simulate", "--sim-options", options, "--json", "--log-dir", LogDir);

        Assert.True(exit == 0, error);
        using var json = JsonDocument.Parse(output);
        var root = json.RootElement;
        Assert.Equal("completed", root.GetProperty("outcome").GetString());
        Assert.Equal(0, root.GetProperty("laserOnTravelCount").GetInt32());
        var log = RunLogStore.Read(root.GetProperty("logPath").GetString()!);
        Assert.Equal(LaserGateProfile.NoWatchdogSentence, log.NoWatchdogAccepted);
        Assert.Equal(LaserGateKind.FrequencyOnly, log.Profile.Gate.Kind);
    }

    [Fact]
    public async Task EngraveSimulate_DefaultProfileWithTheOption_LogsNoAcceptance()
    {
        // The counted-burst gate has its watchdog: the option changes nothing and the log says nothing of it.
        var (exit, output, error) = await CliHarness.RunAsync(
            "engrave", QrCode, "--width-mm", "2", "--origin-mm", "10,10", "--accept-no-watchdog", "--simulate", "--json", "--log-dir", LogDir);

        Assert.True(exit == 0, error);
        using var json = JsonDocument.Parse(output);
        var log = RunLogStore.Read(json.RootElement.GetProperty("logPath").GetString()!);
        Assert.Null(log.NoWatchdogAccepted);
    }

    [Theory]
    [InlineData("frequency-only-silent.json", "laser sent off (this gate never replies, so nothing confirms it)")]
    [InlineData("frequency-only.json", "laser off")]
    public async Task GoToSimulate_FrequencyOnlyGate_MovesAndSaysOnlyWhatTheGateConfirmed(string profile, string laser)
    {
        // A gate that never replies can only be sent off: a move with the laser off goes on, and never says "laser off".
        var (exit, output, error) = await CliHarness.RunAsync(
            "goto", "5", "5", "--simulate", "--profile", Path.Combine(CliHarness.RepositoryRoot, "assets", "profiles", profile));

        Assert.True(exit == 0, error);
        Assert.EndsWith($"= 5, 5 mm; {laser}", output.TrimEnd(), StringComparison.Ordinal);
    }

    public void Dispose() => Directory.Delete(folder, recursive: true);
}
