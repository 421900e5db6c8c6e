using Bunit;
using LaserEngrave.App.Components.Workspace;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Machine;
using NSubstitute;

namespace LaserEngrave.App.Tests.Components;

/// <summary>The Commission panel over its view-model and a fake machine check: one line per step, the beam's confirmation, Stop, the profile and the report.</summary>
public sealed class CommissionPanelTests : ComponentTest
{
    private static readonly LatencyProfile Measured = new() { StageMs = 2.5, StageJitterMs = 0.75, GateMs = 3, GateJitterMs = 1 };

    private IRenderedComponent<CommissionPanel> RenderPanel() => Render<CommissionPanel>(p => p.Add(c => c.Commission, Commission));

    // The button launches the command off the renderer's thread: its task is awaited once it exists.
    private async Task ClickCheckAsync(IRenderedComponent<CommissionPanel> cut)
    {
        cut.Find("#cmCheck").Click();
        cut.WaitForState(() => Commission.CheckCommand.ExecutionTask is not null);
        await Commission.CheckCommand.ExecutionTask!;
    }

    // A check that reports the gate's step, a failed X axis and the watchdog as asked, then ends.
    private void CheckReports(bool? tripSeen = null)
    {
        Checks.RunAsync(Arg.Any<IMachineConnection>(), Arg.Any<MachineProfile>(), Arg.Any<double>(), Arg.Any<int>(), Arg.Any<bool>(), Arg.Any<IProgress<MachineCheckStep>>(), Arg.Any<CancellationToken>())
            .Returns(c =>
            {
                var progress = c.ArgAt<IProgress<MachineCheckStep>>(5);
                var trip = c.ArgAt<bool>(4);
                List<MachineCheckStep> steps =
                [
                    new("laser gate", MachineCheckResult.Passed, "PICGATE FAKE on fake machine, switched off"),
                    new("X axis", MachineCheckResult.Failed, "device 1 (X): device ID 4212, shorter than the profile's 60 mm"),
                    new("latencies", MachineCheckResult.Passed, "stage 2.5 ± 0.75 ms"),
                    trip ? new("gate watchdog", MachineCheckResult.Passed, "watchdog tripped") : new("gate watchdog", MachineCheckResult.Skipped, "not tripped: nobody confirmed the beam was blocked"),
                ];
                foreach (var step in steps)
                {
                    progress.Report(step);
                }

                return new MachineCheckReport(steps, null, null, "PICGATE FAKE", Measured);
            });
    }

    [Fact]
    public async Task Check_NotConfirmed_OneLinePerStepWatchdogSkippedReportAndProfileWritten()
    {
        CheckReports();
        await ConnectAsync();
        var cut = RenderPanel();

        await ClickCheckAsync(cut);

        cut.WaitForAssertion(() => Assert.Contains("NOT every step passed", cut.Find("#commission-result").TextContent, StringComparison.Ordinal));
        var lines = cut.FindAll("#commission-steps li").Select(li => (li.GetAttribute("data-step"), li.GetAttribute("data-result"))).ToList();
        Assert.Equal([("laser gate", "ok"), ("X axis", "FAILED"), ("latencies", "ok"), ("gate watchdog", "skip")], lines);
        await Checks.Received(1).RunAsync(Machine.Connection, Arg.Any<MachineProfile>(), 10, 100, false, Arg.Any<IProgress<MachineCheckStep>>(), Arg.Any<CancellationToken>());

        // As `machine check --profile FILE --write --report FILE`: the latencies into the profile (the app's own when none was chosen), the lines into the report.
        var profilePath = Path.Combine(DataFolder.Path, "machine-profile.json");
        Assert.Equal(Measured, MachineProfile.Load(profilePath).Latency);
        Assert.Equal(Measured, Main.Machine.Profile.Latency);
        Assert.Equal(profilePath, Main.Settings.ProfilePath);
        var report = await File.ReadAllLinesAsync(Commission.ReportPath!, Xunit.TestContext.Current.CancellationToken);
        Assert.Equal("LaserEngrave machine check: fake machine", report[0]);
        Assert.Contains("FAILED X axis: device 1 (X): device ID 4212, shorter than the profile's 60 mm", report);
        Assert.Contains("skip   gate watchdog: not tripped: nobody confirmed the beam was blocked", report);
        Assert.Equal($"Written: the latency section of {profilePath}", report[^1]);
        Assert.Contains(profilePath, cut.Find("#commission-profile").TextContent, StringComparison.Ordinal);
    }

    [Fact]
    public async Task Check_BeamBlockedTickedAndNoWrite_TheWatchdogIsTrippedAndTheProfileLeftAlone()
    {
        CheckReports();
        await ConnectAsync();
        var cut = RenderPanel();
        cut.Find("#cmBeamBlocked").Change(true);
        cut.Find("#cmWrite").Change(false);
        cut.Find("#cmDistance").Change("0,5");

        await ClickCheckAsync(cut);

        await Checks.Received(1).RunAsync(Machine.Connection, Arg.Any<MachineProfile>(), 0.5, 100, true, Arg.Any<IProgress<MachineCheckStep>>(), Arg.Any<CancellationToken>());
        cut.WaitForAssertion(() => Assert.Equal("ok", cut.Find("#commission-steps li[data-step='gate watchdog']").GetAttribute("data-result")));
        Assert.False(File.Exists(Path.Combine(DataFolder.Path, "machine-profile.json")));
        Assert.Equal(MachineProfile.Default.Latency, Main.Machine.Profile.Latency);
        Assert.StartsWith("Not written", cut.Find("#commission-profile").TextContent, StringComparison.Ordinal);
    }

    [Fact]
    public void Check_NotConnected_TheButtonIsDisabled()
    {
        var cut = RenderPanel();

        Assert.True(Disabled(cut.Find("#cmCheck")));
        Assert.True(Disabled(cut.Find("#cmStop")));
    }

    [Fact]
    public async Task Check_DistanceBeyondTheTravel_RefusedInOneLineNothingRuns()
    {
        await ConnectAsync();
        var cut = RenderPanel();
        cut.Find("#cmDistance").Change("61");

        cut.Find("#cmCheck").Click();

        cut.WaitForAssertion(() => Assert.Contains("at most the travel (60 mm)", cut.Find("[data-error='commission']").TextContent, StringComparison.Ordinal));
        await Checks.DidNotReceiveWithAnyArgs().RunAsync(default!, default!, default, default, default, default!, Xunit.TestContext.Current.CancellationToken);
    }

    [Fact]
    public async Task Stop_WhileChecking_TheCheckIsCancelledAndNothingIsWritten()
    {
        var started = new TaskCompletionSource(TaskCreationOptions.RunContinuationsAsynchronously);
        Checks.RunAsync(Arg.Any<IMachineConnection>(), Arg.Any<MachineProfile>(), Arg.Any<double>(), Arg.Any<int>(), Arg.Any<bool>(), Arg.Any<IProgress<MachineCheckStep>>(), Arg.Any<CancellationToken>())
            .Returns(async c =>
            {
                c.ArgAt<IProgress<MachineCheckStep>>(5).Report(new("laser gate", MachineCheckResult.Passed, "PICGATE FAKE, switched off"));
                started.SetResult();
                await Task.Delay(Timeout.Infinite, c.ArgAt<CancellationToken>(6));
                return (MachineCheckReport)null!;
            });
        await ConnectAsync();
        var cut = RenderPanel();

        cut.Find("#cmCheck").Click();
        await started.Task;
        cut.WaitForAssertion(() => Assert.Equal("running", cut.Find("#commission-steps li[data-step='X axis']").GetAttribute("data-result")));
        Assert.True(Main.Activity.IsBusy);
        cut.Find("#cmStop").Click();
        await Commission.CheckCommand.ExecutionTask!;

        cut.WaitForAssertion(() => Assert.Contains("stopped", cut.Find("[data-error='commission']").TextContent, StringComparison.Ordinal));
        Assert.False(Main.Activity.IsBusy);
        Assert.False(Commission.IsChecking);
        Assert.Null(Commission.ReportPath);
        Assert.False(File.Exists(Path.Combine(DataFolder.Path, "machine-profile.json")));
    }
}
