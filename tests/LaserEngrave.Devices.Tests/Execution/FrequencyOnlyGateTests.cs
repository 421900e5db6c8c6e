using System.Globalization;
using System.Text.RegularExpressions;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Burn;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>
/// The gate a lab already has (issue 33, part 4): a PIC that only sets a frequency, with no watchdog. The host times every
/// switch-on (FREQ f) and switch-off (FREQ 0) itself, as before BURST; the twin is that gate.
/// </summary>
public sealed class FrequencyOnlyGateTests(ITestOutputHelper output)
{
    internal static MachineProfile Profile(string file = "frequency-only.json") => MachineProfile.Load(TestJobs.AssetPath(Path.Combine("profiles", file)));

    internal static PreparedJob Job(string asset, MachineProfile profile, PlanStrategy strategy = PlanStrategy.Optimized) =>
        PreparedJob.Prepare(new JobSpec
        {
            Profile = profile,
            ImagePath = TestJobs.AssetPath(asset),
            Size = SizeSpec.Width(5),
            Origin = TestJobs.Origin,
            Plan = new PlanOptions { Strategy = strategy },
        });

    private static readonly RunOptions Accepted = new() { AcceptNoWatchdog = true };

    [Theory(Timeout = 300_000)]
    [InlineData("qr-code.bmp", PlanStrategy.Optimized, "frequency-only.json")]
    [InlineData("text-banner.png", PlanStrategy.Optimized, "frequency-only.json")]
    [InlineData("line-drawing.png", PlanStrategy.Optimized, "frequency-only.json")]
    [InlineData("qr-code.bmp", PlanStrategy.Paper, "frequency-only.json")]
    [InlineData("qr-code.bmp", PlanStrategy.Optimized, "frequency-only-silent.json")]
    public async Task RunAsync_FrequencyOnlyGateSample_CompletesWithTheMaskAndNoPulseOnWhite(string asset, PlanStrategy strategy, string profileFile)
    {
        var ct = TestContext.Current.CancellationToken;

        // A host never late (the in-process twin's default) needs no allowance for late switch-offs: the default tolerance.
        var profile = Profile(profileFile) with { EdgeToleranceUm = MachineProfile.Default.EdgeToleranceUm };
        await using var run = SimulatedRun.Create(profile: profile);
        var job = Job(asset, profile, strategy);

        var result = await run.Do(() => run.Executor(job, Accepted).RunAsync(ct));
        var report = run.Analyze(job);

        output.WriteLine(string.Create(CultureInfo.InvariantCulture, $"{asset} {strategy} {profileFile}: {result.Outcome} {result.FaultMessage}; engraving {result.EngravingDuration.TotalSeconds:0.00} s (estimate {result.EstimatedSeconds:0.00} s); on white {report.LaserOnTravelCount}, extra {report.ExtraPixels}, missing {report.MissingPixels}, edges mean/max {report.Edges?.MeanErrorUm:0.00}/{report.Edges?.MaxErrorUm:0.00} µm, dwells {report.DwellCount}"));
        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        Assert.Equal(LaserGateKind.FrequencyOnly, run.Machine.Gate.Kind);
        Assert.Equal(0, run.Machine.Gate.WatchdogMs);
        Assert.Equal(0, report.LaserOnTravelCount);
        Assert.True(report.Burned.ContentEquals(job.Mask), $"{report.ExtraPixels} extra, {report.MissingPixels} missing");
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Theory(Timeout = 300_000)]
    [InlineData("qr-code.bmp", 1.0)]
    [InlineData("text-banner.png", 0.95)]
    public async Task RunAsync_FrequencyOnlyGateLateHostExampleProfile_CompletesWithNoPulseOnWhite(string asset, double burnSpeedMmPerS)
    {
        // The example profile's 5 µm tolerance aims every switch-off that early, so a computer up to 5 ms late (the
        // twin's realistic host) still stops the gate before the edge; the banner's 16.2 ms pixels then need <= 0.972 mm/s.
        var ct = TestContext.Current.CancellationToken;
        var profile = Profile();
        // A write stalled 5-30 ms is beyond what aiming early can absorb: a frequency-only gate fires until its switch-off
        // arrives, so this host wakes and reads late but never stalls a write (docs/execution.md, "A frequency-only gate").
        var lateness = LaserEngrave.Simulator.Timing.HostLateness.Realistic with { StallProbability = 0 };
        await using var run = SimulatedRun.Create(new SimulatorOptions { HostLateness = lateness }, profile);
        var job = PreparedJob.Prepare(Job(asset, profile).Spec with { Process = ProcessSettings.Default with { BurnSpeedMmPerS = burnSpeedMmPerS } });

        var log = new RecordingLog();

        // The session, as both front ends run it: a switch-on the late host sends beyond the tolerance is a timing doubt it goes on from.
        var session = new EngraveSession(
            new EngraveMachine(run.Stage, run.Gate, run.Time, "simulator", "simulator") { Simulated = true, Inspector = new BurnInspector(run.Machine) },
            job,
            new EngraveSessionOptions { Log = log, AcceptNoWatchdog = true });

        await session.RunAsync(null, ct);
        var record = Assert.Single(log.Records);
        var simulation = Assert.IsType<RunSimulation>(record.Simulation);

        output.WriteLine(string.Create(CultureInfo.InvariantCulture, $"{asset} at {burnSpeedMmPerS} mm/s, late host: {record.Outcome} {record.Fault?.Message}; recoveries {record.Recoveries?.Count ?? 0}; on white {simulation.LaserOnTravelCount}, extra {simulation.ExtraPixels}, missing {simulation.MissingPixels}, edges mean/max {simulation.Edges?.MeanErrorUm:0.00}/{simulation.Edges?.MaxErrorUm:0.00} µm"));
        Assert.True(record.Outcome == RunOutcome.Completed, $"{record.Outcome}: {record.Fault?.Message}");
        Assert.Equal((0, 0L, 0L), (simulation.LaserOnTravelCount, simulation.ExtraPixels, simulation.MissingPixels));
        Assert.Equal(LaserGateProfile.NoWatchdogSentence, record.NoWatchdogAccepted);
        Assert.Contains("No watchdog", RunSummaryText.Format(record), StringComparison.Ordinal);
    }

    [Fact]
    public void PixelTooShort_FrequencyOnlyGateWithItsToleranceAhead_NamesTheSlowerSpeed()
    {
        // A frequency-only gate's switch-off is aimed 5 µm (5 ms at 1 mm/s) early, so it needs longer pixels than the
        // counted-burst gate: the longest pixel it refuses at 1 mm/s is one the counted-burst gate switches exactly.
        var profile = Profile();
        var frequencyOnly = TimedSwitching.For(ProcessSettings.Default, profile, profile.X.MicrostepUm);
        var counted = TimedSwitching.For(ProcessSettings.Default, MachineProfile.Default, profile.X.MicrostepUm);
        var pitchUm = 20.0;
        while (frequencyOnly.PixelTooShort((long)Math.Round(pitchUm / profile.X.MicrostepUm), pitchUm) is null)
        {
            pitchUm -= 0.25;
        }

        var pixel = (long)Math.Round(pitchUm / profile.X.MicrostepUm);
        Assert.Null(counted.PixelTooShort(pixel, pitchUm));
        var refused = frequencyOnly.PixelTooShort(pixel, pitchUm);
        output.WriteLine(string.Create(CultureInfo.InvariantCulture, $"{pitchUm} µm: {refused}"));
        var slowest = double.Parse(Regex.Match(refused!, @"burn at ([0-9.]+) mm/s").Groups[1].Value, CultureInfo.InvariantCulture);
        Assert.InRange(slowest, 0.5, 0.9999);
        Assert.Equal(0.005, frequencyOnly.OffAdvanceSeconds - frequencyOnly.EdgeGuardSeconds, 6);
        Assert.Equal(counted.EdgeGuardSeconds, counted.OffAdvanceSeconds);
    }

    [Fact(Timeout = 300_000)]
    public async Task RunAsync_FrequencyOnlyGateDrawing_CompletesOnItsPath()
    {
        var ct = TestContext.Current.CancellationToken;
        var profile = Profile();
        var spec = new JobSpec { Profile = profile, ImagePath = Path.Combine(Path.GetDirectoryName(TestJobs.AssetPath("qr-code.bmp"))!, "drawings", "hexagons.dxf"), Size = SizeSpec.Width(5), Origin = new OriginMm(5, 5) };
        var job = PreparedDrawing.Prepare(spec, VectorOptions.Default, null);
        await using var run = SimulatedRun.Create(profile: profile);

        var result = await run.Do(() => new RunExecutor(run.Stage, run.Gate, job, run.Time, Accepted).RunAsync(ct));
        var report = run.Machine.Recorder.AnalyzePaths(job.Plan.Paths, job.Spec.Process.BurnSpeedMmPerS);

        output.WriteLine(string.Create(CultureInfo.InvariantCulture, $"hexagons.dxf: {result.Outcome} {result.FaultMessage}; deviation max {report.DeviationMaxUm:0.###} µm, off path {report.OffPathPulses}, dwells {report.DwellCount}, {report.Pulses} pulses"));
        Assert.True(result.Outcome == RunOutcome.Completed, $"{result.Outcome}: {result.FaultMessage}");
        Assert.True(report.Pulses > 0);
        Assert.Equal(0, report.OffPathPulses);
        Assert.False(run.Machine.Gate.IsFiring);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_NoWatchdogNotAccepted_RefusedWithTheSentenceBeforeTheGateHearsAnything()
    {
        var ct = TestContext.Current.CancellationToken;
        var profile = Profile();
        await using var run = SimulatedRun.Create(profile: profile);
        var job = Job("qr-code.bmp", profile);
        var executor = run.Executor(job);

        var refused = await Assert.ThrowsAsync<PreflightException>(() => run.Do(() => executor.RunAsync(ct)));

        Assert.Contains(LaserGateProfile.NoWatchdogSentence, refused.Message, StringComparison.Ordinal);
        Assert.Contains("--accept-no-watchdog", refused.Message, StringComparison.Ordinal);
        Assert.DoesNotContain('\n', refused.Message);
        Assert.Empty(run.Machine.Recorder.LaserOnIntervals(run.Machine.NowSeconds));
        Assert.Equal(RunState.Failed, executor.State);
    }

    [Fact(Timeout = 120_000)]
    public async Task RunAsync_FrequencyOnlyGateDotJob_RefusedInPreflight()
    {
        var ct = TestContext.Current.CancellationToken;
        var profile = Profile();
        await using var run = SimulatedRun.Create(profile: profile);
        var job = PreparedJob.Prepare(new JobSpec
        {
            Profile = profile,
            ImagePath = TestJobs.AssetPath("qr-code.bmp"),
            Size = SizeSpec.Width(2),
            Origin = TestJobs.Origin,
            Process = ProcessSettings.Default with { Mode = PlanMode.Dots, PulsesPerDot = 10 },
        });

        var refused = await Assert.ThrowsAsync<PreflightException>(() => run.Do(() => run.Executor(job, Accepted).RunAsync(ct)));

        Assert.Contains("only a gate that counts its bursts (BURST) can do", refused.Message, StringComparison.Ordinal);
    }

    [Fact(Timeout = 120_000)]
    public async Task FirePulsesAsync_FrequencyOnlyGate_FiresTheCountTimedByTheHost()
    {
        var ct = TestContext.Current.CancellationToken;
        var profile = Profile();
        await using var run = SimulatedRun.Create(profile: profile);

        await run.Do(() => run.TestMoves().FirePulsesAsync(100, 1000, ct));
        var on = Assert.Single(run.Machine.Recorder.LaserOnIntervals(run.Machine.NowSeconds));

        // FREQ 1000 on, FREQ 0 timed to act 99.5 periods after it: 100 pulses, give or take one for the two lines'
        // latencies (adapters ±0.5 ms and processing ±0.2 ms each, ±1.4 ms in all); a count the gate cannot make exact.
        output.WriteLine(string.Create(CultureInfo.InvariantCulture, $"on for {(on.To - on.From) * 1000:0.00} ms"));
        Assert.InRange(on.To - on.From, 0.0980, 0.1010);
        Assert.False(run.Machine.Gate.IsFiring);
    }
}
