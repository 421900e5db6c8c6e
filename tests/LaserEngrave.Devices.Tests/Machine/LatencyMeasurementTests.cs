using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Machine;

namespace LaserEngrave.Devices.Tests.Machine;

public class LatencyMeasurementTests
{
    [Fact]
    public void HostWaitsOf_HundredWaits_98thByRankAndTheLatest()
    {
        // 0.01 .. 0.99 ms and an early wake-up (-0.2 ms), which counts as 0: sorted, the 98th of the 100 is 0.97.
        var waits = Enumerable.Range(1, 99).Select(i => i / 100.0).Append(-0.2).ToList();

        var host = HostWaits.Of(waits);

        Assert.Equal((100, 0.97, 0.99), (host.Count, host.Percentile98Ms, host.MaxMs));
    }

    [Fact]
    public void ToProfile_HostNotMeasured_KeepsTheProfilesLateness()
    {
        var trips = new RoundTrips("X", 10, 14, 14.5, 15, 0.3, 12.5);

        var latency = new LatencyMeasurement(trips, trips, trips).ToProfile(new LatencyProfile { HostLatenessMs = 0.7, HostLatenessTailMs = 9 });

        Assert.Equal((0.7, 9.0), (latency.HostLatenessMs, latency.HostLatenessTailMs));
    }

    [Fact]
    public void ToProfile_RoundTrips_OneWayIsRoundTripLessWireHalved_ProcessingKept()
    {
        // Stage: mean 14.5 ms, wire 12.5 ms -> 1.0 ms each way; both axes s = 0.6 ms over 100 round trips, pooled over
        // 200: s² = 2 x 99 x 0.36 / 199 -> h = sqrt(3 s² / 2) = 0.7330 ms.
        // Gate: mean 17 ms, wire 13 ms, processing kept 1 ms -> 1.5 ms each way; s = 0.5 ms, hp = 0.3 ms ->
        // h = sqrt((3 x 0.25 - 0.09) / 2) = 0.5745 ms.
        // The extremes are within what those half-widths allow (|d| <= 2 h + hp), so the variance decides.
        var stage = new RoundTrips("X", 100, 13.1, 14.5, 15.9, 0.6, 12.5);
        var gate = new RoundTrips("gate", 100, 16, 17, 18, 0.5, 13);
        var kept = new LatencyProfile { GateProcessingMs = 1, GateProcessingJitterMs = 0.3 };

        var latency = new LatencyMeasurement(stage, stage with { Device = "Y" }, gate).ToProfile(kept);

        Assert.Equal(1.0, latency.StageMs, 12);
        Assert.Equal(Math.Sqrt(1.5 * 2 * 99 * 0.36 / 199), latency.StageJitterMs, 12);
        Assert.Equal(1.5, latency.GateMs, 12);
        Assert.Equal(Math.Sqrt(0.33), latency.GateJitterMs, 12);
        Assert.Equal(1, latency.GateProcessingMs);
        Assert.Equal(0.3, latency.GateProcessingJitterMs);
    }

    [Fact]
    public void ToProfile_ALateRoundTripBeyondTheVariance_TheHalfWidthCoversIt()
    {
        // Hundreds of round trips within ±0.5 ms and one 9 ms late (a busy computer): s = 0.6 ms would give h = 0.73 ms,
        // which does not cover it; the furthest needs 2 h + hp >= 9 ms.
        var stage = new RoundTrips("X", 300, 14, 14.5, 23.5, 0.6, 12.5);
        var gate = new RoundTrips("gate", 300, 16.5, 17, 26, 0.6, 13);
        var kept = new LatencyProfile { GateProcessingMs = 1, GateProcessingJitterMs = 0.2 };

        var latency = new LatencyMeasurement(stage, stage with { Device = "Y" }, gate).ToProfile(kept);

        Assert.Equal(4.5, latency.StageJitterMs, 12);
        Assert.Equal((9 - 0.2) / 2, latency.GateJitterMs, 12);
    }

    [Fact]
    public void ToProfile_RoundTripBelowWireAndProcessing_IsZeroNotNegative()
    {
        var trips = new RoundTrips("X", 10, 12.39, 12.4, 12.41, 0.01, 12.5);
        var latency = new LatencyMeasurement(trips, trips, trips).ToProfile(new LatencyProfile());

        Assert.Equal(0, latency.StageMs);
        Assert.Equal(0, latency.GateMs);
        Assert.Equal(0, latency.GateJitterMs);
        Assert.Empty(MachineProfileValidator.Problems(MachineProfile.Default with { Latency = latency }));
    }

    [Fact]
    public void With_TwoSets_IsTheFiguresOfAllTheRoundTripsTogether()
    {
        double[] a = [13.1, 14.2, 15.0, 14.4], b = [13.9, 15.3, 14.0];
        var both = RoundTrips.Of("X", a, 12.5).With(RoundTrips.Of("Y", b, 12.5), "stage");
        var all = RoundTrips.Of("stage", [.. a, .. b], 12.5);

        Assert.Equal(all.Count, both.Count);
        Assert.Equal(all.MinMs, both.MinMs);
        Assert.Equal(all.MaxMs, both.MaxMs);
        Assert.Equal(all.MeanMs, both.MeanMs, 12);
        Assert.Equal(all.StdDevMs, both.StdDevMs, 12);
        Assert.Equal(1.1, all.SpreadMs, 12);
    }
}
