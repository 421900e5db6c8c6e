using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Planning;

public class LowerBoundTests
{
    // Default process on a T-LA (PlanEstimatorTests has the arithmetic): burn 1075 units = 10078.125 µsteps/s,
    // travel 4300 units = 40312.5 µsteps/s, acceleration 45 units = 506250 µsteps/s². Flying a gap (up from the burn speed
    // and back) beats both crossing it at the burn speed and a stop-go move from rest.
    private const double BurnSpeed = 10078.125;
    private const double TravelSpeed = 40312.5;
    private const double Acceleration = 506250;

    [Fact]
    public void ComputeStatistics_GapsInARow_TakeTheShortestOfBurnSpeedFlownAndStopGo()
    {
        // Pitch 100 microsteps: burns 0..100, 200..400, 1400..1800 (700 microsteps). Both gaps are flown: from the burn
        // speed up at the acceleration and back, never reaching the travel speed: 2 (sqrt(vb² + a d) - vb) / a, that is
        // 8.93 ms for the 100-microstep gap (against 9.92 ms at the burn speed) and 57.58 ms for the 1000-microstep one
        // (against an 88.89 ms stop-go triangle).
        var mask = TestMasks.FromRows("#.##..........####");
        var stats = new RasterPlan(mask, TestMasks.Geometry(mask, pitch: 100)).ComputeStatistics(ProcessSettings.Default);

        static double Flown(double d) => 2 * (Math.Sqrt((BurnSpeed * BurnSpeed) + (Acceleration * d)) - BurnSpeed) / Acceleration;
        var expected = (700 / BurnSpeed) + Flown(100) + Flown(1000);
        Assert.Equal(0.135964, expected, 6);
        Assert.True(Flown(100) < 100 / BurnSpeed && Flown(1000) < 2 * Math.Sqrt(1000 / Acceleration));
        Assert.Equal(expected, stats.LowerBoundSeconds, 12);
    }

    [Fact]
    public void ComputeStatistics_RowChange_IsTheLongerAxisRestToRest_FollowingTheSerpentine()
    {
        // Pitch 10000: row 0 burns 0 -> 10000 at y 5000; row 1 is run right to left, entered at 100000, at y 15000.
        // The change: X 90000 microsteps, v/a + d/v = 0.079630 + 2.232558 = 2.312188 s; Y 10000, 0.327692 s.
        var mask = TestMasks.FromRows("#.........", ".........#");
        var stats = new RasterPlan(mask, TestMasks.Geometry(mask, pitch: 10_000)).ComputeStatistics(ProcessSettings.Default);

        var expected = (20_000 / BurnSpeed) + (TravelSpeed / Acceleration) + (90_000 / TravelSpeed);
        Assert.Equal(4.296684, expected, 6);
        Assert.Equal(expected, stats.LowerBoundSeconds, 12);
    }

    [Fact]
    public void ComputeStatistics_Unidirectional_RowChangeGoesBackToTheLeftEdge()
    {
        // Row 1 left to right is entered at 90000: the change is 80000 microsteps in X.
        var mask = TestMasks.FromRows("#.........", ".........#");
        var plan = new RasterPlan(mask, TestMasks.Geometry(mask, pitch: 10_000), new PlanOptions { Bidirectional = false });

        var expected = (20_000 / BurnSpeed) + (TravelSpeed / Acceleration) + (80_000 / TravelSpeed);
        Assert.Equal(expected, plan.ComputeStatistics(ProcessSettings.Default).LowerBoundSeconds, 12);
    }

    [Fact]
    public void ComputeStatistics_Overscan_LeavesTheBoundAlone_AndTheEstimateAboveIt()
    {
        var mask = TestMasks.FromRows("##..##....#", "..###...##.", "...........", "#.........#");
        var geometry = TestMasks.Geometry(mask, pitch: 1500, ox: 20_000);
        var plain = new RasterPlan(mask, geometry).ComputeStatistics(ProcessSettings.Default);
        var overscan = new RasterPlan(mask, geometry, new PlanOptions { OverscanMm = 0.1 }).ComputeStatistics(ProcessSettings.Default);

        Assert.Equal(plain.LowerBoundSeconds, overscan.LowerBoundSeconds, 12);
        Assert.True(plain.LowerBoundSeconds < plain.EngravingSeconds);
        Assert.Equal(plain.LowerBoundSeconds, LowerBound.Of(new RasterPlan(mask, geometry), ProcessSettings.Default), 12);
    }

    [Fact]
    public void ComputeStatistics_BlankMask_IsZero()
    {
        var mask = TestMasks.FromRows("....", "....");
        Assert.Equal(0, new RasterPlan(mask, TestMasks.Geometry(mask)).ComputeStatistics(ProcessSettings.Default).LowerBoundSeconds);
    }
}
