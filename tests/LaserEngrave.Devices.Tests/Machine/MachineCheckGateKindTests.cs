using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Machine;
using LaserEngrave.Devices.Tests.Execution;
using LaserEngrave.Simulator;

namespace LaserEngrave.Devices.Tests.Machine;

/// <summary>Commissioning tells the counted-burst gate from the frequency-only one, and says which it found (issue 33, part 4).</summary>
public sealed class MachineCheckGateKindTests(ITestOutputHelper output)
{
    private static MachineProfile FrequencyOnly(bool neverReplies = false) => MachineProfile.Default with
    {
        Gate = new LaserGateProfile { Kind = LaserGateKind.FrequencyOnly, NeverReplies = neverReplies, WatchdogMs = 0, OffCommand = "FREQ 0", IdentifyCommand = neverReplies ? "" : "*IDN?" },
    };

    private static async Task<MachineCheckReport> CheckAsync(MachineProfile profile, LaserGateKind twin)
    {
        await using var run = SimulatedRun.Create(new SimulatorOptions { GateKind = twin }, profile);
        var check = new MachineCheck(run.Stage, run.Gate, profile, run.Time);
        return await run.Do(() => check.RunAsync(1, 10, tripWatchdog: true, TestContext.Current.CancellationToken));
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_CountedBurstGateCountedBurstProfile_SaysItFoundTheCountedBurstGateAndPasses()
    {
        var report = await CheckAsync(MachineProfile.Default, LaserGateKind.CountedBurst);

        Assert.Equal(LaserGateKind.CountedBurst, report.GateKindFound);
        Assert.Contains("found a counted-burst gate with a watchdog", report.Steps[0].Finding, StringComparison.Ordinal);
        Assert.True(report.Passed, string.Join("\n", report.Steps.Select(s => $"{s.Result} {s.Name}: {s.Finding}")));
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_FrequencyOnlyGateFrequencyOnlyProfile_SaysItFoundAFrequencyOnlyGateWatchdogNoneToTripPasses()
    {
        var report = await CheckAsync(FrequencyOnly(), LaserGateKind.FrequencyOnly);
        foreach (var line in report.Lines("twin", DateTimeOffset.UnixEpoch))
        {
            output.WriteLine(line);
        }

        Assert.Equal(LaserGateKind.FrequencyOnly, report.GateKindFound);
        Assert.Contains("found a frequency-only gate", report.Steps[0].Finding, StringComparison.Ordinal);
        var watchdog = report.Steps.Single(s => s.Name == "gate watchdog");
        Assert.Equal(MachineCheckResult.Skipped, watchdog.Result);
        Assert.Contains(LaserGateProfile.NoWatchdogSentence, watchdog.Finding, StringComparison.Ordinal);
        Assert.True(report.Passed, string.Join("\n", report.Steps.Select(s => $"{s.Result} {s.Name}: {s.Finding}")));
        Assert.Contains("this gate has no watchdog", report.Lines("twin", DateTimeOffset.UnixEpoch).Last(), StringComparison.Ordinal);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_FrequencyOnlyGateCountedBurstProfile_GateStepFailsNamingWhatToSet()
    {
        var report = await CheckAsync(MachineProfile.Default, LaserGateKind.FrequencyOnly);

        Assert.Equal(LaserGateKind.FrequencyOnly, report.GateKindFound);
        Assert.Equal(MachineCheckResult.Failed, report.Steps[0].Result);
        Assert.Contains("found a frequency-only gate", report.Steps[0].Finding, StringComparison.Ordinal);
        Assert.Contains("set gate.kind to frequencyOnly", report.Steps[0].Finding, StringComparison.Ordinal);
        Assert.False(report.Passed);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_CountedBurstGateFrequencyOnlyProfile_SaysTheGateCouldDoMore()
    {
        var report = await CheckAsync(FrequencyOnly(), LaserGateKind.CountedBurst);

        Assert.Equal(LaserGateKind.CountedBurst, report.GateKindFound);
        Assert.Contains("though the profile says frequencyOnly: set gate.kind to countedBurst", report.Steps[0].Finding, StringComparison.Ordinal);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_GateThatNeverReplies_SaysItsKindCannotBeAskedAndTheLatencyNotMeasured()
    {
        var report = await CheckAsync(FrequencyOnly(neverReplies: true), LaserGateKind.FrequencyOnly);

        Assert.Null(report.GateKindFound);
        Assert.Contains("never replies", report.Steps[0].Finding, StringComparison.Ordinal);
        Assert.Equal(MachineCheckResult.Failed, report.Steps.Single(s => s.Name == "latencies").Result);
        Assert.False(report.Passed);
    }
}
