using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Sweeps;

namespace LaserEngrave.Core.Tests.Jobs;

/// <summary>What this computer can hold with this gate (issue 34), checked by hand against the profile's lateness and tolerance.</summary>
public class SpeedHoldTests
{
    private static SweepSpec Sweep(string rows, MachineProfile profile) => new()
    {
        Rows = SweepAxis.Parse(rows, "--rows"),
        Columns = SweepAxis.Parse("frequency=500,1000", "--columns"),
        Origin = new OriginMm(5, 5),
        CellMm = 1,
        SpacingMm = 0.5,
        PitchUm = 50,
        Profile = profile,
    };

    [Fact]
    public void FastestMmPerS_HostTimedDefaultProfile_IsToleranceOverLateness()
    {
        // 1.5 µm / 0.5 ms: a lab PC's lateness at the default tolerance.
        Assert.Equal(3.0, SpeedHold.FastestMmPerS(MachineProfile.Default, scheduled: false), 9);
    }

    [Fact]
    public void FastestMmPerS_ScheduledGateLatenessWithinTheLead_HoldsAnySpeed()
    {
        Assert.Equal(double.PositiveInfinity, SpeedHold.FastestMmPerS(MachineProfile.Default, scheduled: true));
    }

    [Fact]
    public void FastestMmPerS_ScheduledGateLatenessBeyondTheLead_IsToleranceOverLateness()
    {
        // Waits 8 ms late pass the 6 ms the plan leaves ahead of a switch-on: they go plain, the tolerance rules them.
        var profile = MachineProfile.Default with { Latency = new LatencyProfile { HostLatenessMs = 8 } };

        Assert.Equal(1.5 / 8, SpeedHold.FastestMmPerS(profile, scheduled: true), 9);
    }

    [Fact]
    public void FastestMmPerS_FrequencyOnlyGateAskedAsScheduled_IsToleranceOverLateness()
    {
        var profile = MachineProfile.Default with { Gate = new LaserGateProfile { Kind = LaserGateKind.FrequencyOnly, WatchdogMs = 0 } };

        Assert.Equal(3.0, SpeedHold.FastestMmPerS(profile, scheduled: true), 9);
    }

    [Fact]
    public void Problem_FourMmPerSHostTimed_NamesTheLatenessAndTheFastestSpeed()
    {
        var problem = SpeedHold.Problem(4, MachineProfile.Default, scheduled: false);

        Assert.Equal(
            "burn speed 4 mm/s is faster than this computer can hold with this gate: it wakes up to 0.5 ms late (the profile's latency.hostLatenessMs), 2 µm at 4 mm/s, past the edge tolerance of 1.5 µm; the fastest it holds is 3 mm/s (a gate that times its switch-ons, CAPS? listing AFTER, holds any)",
            problem);
    }

    [Theory]
    [InlineData(3.0, false)]
    [InlineData(4.0, true)]
    public void Problem_AtOrBelowTheFastest_IsNull(double speed, bool scheduled)
    {
        Assert.Null(SpeedHold.Problem(speed, MachineProfile.Default, scheduled));
    }

    [Fact]
    public void SweepProblem_RowsBeyondTheFastest_NamesEveryCellAtThoseSpeeds()
    {
        var plan = SweepPlan.Build(Sweep("speed=1,2,3.2,4", MachineProfile.Default));

        var problem = SweepSpeedHold.Problem(plan.Cells, MachineProfile.Default, scheduled: false);

        Assert.NotNull(problem);
        Assert.StartsWith("4 cells of the sweep (cell row 3, column 1 (", problem, StringComparison.Ordinal);
        Assert.Contains("cell row 4, column 2 (", problem, StringComparison.Ordinal);
        Assert.DoesNotContain("cell row 2,", problem, StringComparison.Ordinal);
        Assert.Contains("the fastest it holds is 3 mm/s: sweep speeds up to that", problem, StringComparison.Ordinal);
    }

    [Fact]
    public void SweepProblem_ManyCellsBeyond_NamesThemByTheirSpeeds()
    {
        var plan = SweepPlan.Build(Sweep("speed=1,3.2,3.6,4", MachineProfile.Default));

        var problem = SweepSpeedHold.Problem(plan.Cells, MachineProfile.Default, scheduled: false);

        Assert.StartsWith("6 cells of the sweep (every cell at 3.2, 3.6, 4 mm/s) burn faster than this computer can hold with this gate: it wakes up to 0.5 ms late", problem, StringComparison.Ordinal);
    }

    [Fact]
    public void SweepProblem_ScheduledGate_IsNull()
    {
        var plan = SweepPlan.Build(Sweep("speed=1,4", MachineProfile.Default));

        Assert.Null(SweepSpeedHold.Problem(plan.Cells, MachineProfile.Default, scheduled: true));
    }
}
