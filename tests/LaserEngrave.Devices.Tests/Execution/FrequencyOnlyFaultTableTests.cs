using System.Globalization;
using System.Text;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>
/// The fault table on the frequency-only gate (issue 33, part 4): every fault kind of the simulator on the gate at the
/// first switch-on, a switch-off mid-job (the laser on when it strikes) and the last switch-off, and on the stage mid-job,
/// with both strategies, on the QR at 5 mm. Such a gate has no watchdog and no burst: what stops the laser is the host's
/// switch-off alone, and a gate that hears nothing more fires on. The table is written to
/// frequency-only-fault-table.md in the test output folder (docs/execution.md holds it).
/// </summary>
public sealed class FrequencyOnlyFaultTableTests(ITestOutputHelper output)
{
    private static readonly string[] GateKinds = ["drop-reply", "corrupt", "delay", "error", "silent", "disconnect", "no-ack"];
    private static readonly string[] StageKinds = ["drop-reply", "corrupt", "delay", "error", "silent", "disconnect"];

    // Kinds after which the gate still hears the host: the laser must end off, whatever else happened.
    private static readonly string[] GateListens = ["drop-reply", "corrupt", "delay", "error", "no-ack"];

    [Theory(Timeout = 600_000)]
    [InlineData(PlanStrategy.Optimized)]
    [InlineData(PlanStrategy.Paper)]
    public async Task RunAsync_EveryFaultOnTheFrequencyOnlyGate_LaserOffWhenHeardAndNeverConfirmedWhenNot(PlanStrategy strategy)
    {
        var ct = TestContext.Current.CancellationToken;
        var profile = FrequencyOnlyGateTests.Profile();
        var job = FrequencyOnlyGateTests.Job("qr-code.bmp", profile, strategy);
        var options = new RunOptions { AcceptNoWatchdog = true };
        long runs;
        await using (var clean = SimulatedRun.Create(profile: profile))
        {
            runs = (await clean.Do(() => clean.Executor(job, options).RunAsync(ct))).RunsTotal;
        }

        // The gate's lines: 1 preflight's FREQ 0, then each run's FREQ 1000 (line 2r) and FREQ 0 (line 2r + 1).
        var points = new (string Where, string Target, long After)[]
        {
            ("first switch-on", "gate", 1),
            ("switch-off mid-job", "gate", 2 * (runs / 2)),
            ("last switch-off", "gate", 2 * runs),
        };
        var faults = new List<(string Spec, string Kind, string Where, string Target)>();
        foreach (var (where, target, after) in points)
        {
            faults.AddRange(GateKinds.Select(kind => (Spec(kind, target, after), kind, where, target)));
        }

        // The stage mid-job: step by step a stage reply is awaited with the laser on; timed switching never waits for one then.
        faults.AddRange(StageKinds.Select(kind => (Spec(kind, "stage", 250), kind, "stage mid-job", "stage")));

        var table = new StringBuilder();
        table.AppendLine(CultureInfo.InvariantCulture, $"| strategy | fault | where | outcome | laser off | pulses on white | gate firing 2 s after the run |");
        table.AppendLine("|---|---|---|---|---|---|---|");
        var problems = new List<string>();
        foreach (var (spec, kind, where, target) in faults)
        {
            await using var run = SimulatedRun.Create(new SimulatorOptions { FaultSpec = spec }, profile);
            var result = await run.Do(() => run.Executor(job, options).RunAsync(ct));
            var onWhite = run.Analyze(job).LaserOnTravelCount;
            await run.Do(() => Task.Delay(TimeSpan.FromSeconds(2), run.Time, ct));
            var firing = run.Machine.Gate.IsFiring;
            var off = result.LaserOffConfirmed ? $"confirmed ({result.LaserOffBy?.ToString() ?? "run's end"})" : "NOT confirmed";
            table.AppendLine(CultureInfo.InvariantCulture, $"| {strategy} | `{spec}` | {where} | {result.Outcome} | {off} | {onWhite} | {(firing ? "yes: only the interlock or the key stops it" : "no")} |");
            output.WriteLine($"{spec} ({where}): {result.Outcome}: {result.FaultMessage}");

            // Never "confirmed" while the twin's gate still fires.
            if (firing && result.LaserOffConfirmed)
            {
                problems.Add($"{spec}: the laser was reported confirmed off, but the gate still fires");
            }

            if (target == "gate" && GateListens.Contains(kind) && firing)
            {
                problems.Add($"{spec}: the gate still heard the host, yet fires on");
            }

            if (target == "stage" && firing)
            {
                problems.Add($"{spec}: a stage fault left the laser firing");
            }

            if (firing && !(result.FaultMessage ?? string.Empty).Contains("a person must", StringComparison.Ordinal))
            {
                problems.Add($"{spec}: the laser fires on, and the fault does not tell a person to act: {result.FaultMessage}");
            }
        }

        output.WriteLine(table.ToString());
        await File.WriteAllTextAsync(Path.Combine(AppContext.BaseDirectory, $"frequency-only-fault-table-{strategy}.md"), table.ToString(), ct);
        Assert.True(problems.Count == 0, string.Join(Environment.NewLine, problems));
    }

    private static string Spec(string kind, string target, long after) =>
        kind == "delay" ? $"delay:{target}:after={after}:ms=300" : $"{kind}:{target}:after={after}";
}
