using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Machine;
using LaserEngrave.Machines;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.LaserGate;
using LaserEngrave.Simulator.Timing;

namespace LaserEngrave.Devices.Tests.Machine;

public class LatencyProbeTests
{
    private static async Task<LatencyMeasurement> MeasureAsync(SimulatorOptions options, int exchanges = 300)
    {
        var ct = TestContext.Current.CancellationToken;
        var session = MachineFactory.OpenTwin(MachineProfile.Default, options).Session;
        await using (session)
        {
            var probe = new LatencyProbe(session.Stage, session.Gate, session.TimeProvider);
            return await session.RunAsync(() => probe.MeasureAsync(exchanges, ct));
        }
    }

    [Fact(Timeout = 30_000)]
    public async Task MeasureAsync_DefaultSimulator_GivesTheSimulatorsLatencies()
    {
        // The simulator's defaults (docs/simulator.md): the adapter adds 1 ± 0.5 ms each way; the gate takes the reference
        // firmware's time, for the probe's PING (5 bytes) 0.055 ms, where the profile keeps 0.19 ms (a BURST's): the
        // measurement takes the difference for the adapter's, half of it each way.
        var measured = await MeasureAsync(new SimulatorOptions());
        var latency = measured.ToProfile(new LatencyProfile());
        var pingMs = (GateFirmwareTiming.StopBaseCyclesFrequency + (5 * GateFirmwareTiming.CyclesPerLineByte)) / GateFirmwareTiming.ClockHz * 1000;

        Assert.Equal(1.0, latency.StageMs, 0.05);
        Assert.Equal(0.5, latency.StageJitterMs, 0.05);
        Assert.Equal(1.0 + ((pingMs - 0.19) / 2), latency.GateMs, 0.05);
        Assert.Equal(0.5, latency.GateJitterMs, 0.05);
        Assert.Equal(0.19, latency.GateProcessingMs);
        Assert.Equal(0.03, latency.GateProcessingJitterMs);
    }

    [Theory(Timeout = 30_000)]
    [InlineData(1)]
    [InlineData(2)]
    public async Task MeasureAsync_LabPcHost_HostLatenessItsTypicalAndTheTailSeen(int seed)
    {
        // The twin's realistic host: waits up to 0.5 ms late, 1 in 100 up to 5 ms. Seed 2 puts more than ten of 1000 waits
        // in the tail, which a 99th percentile took for the typical lateness (0.99 ms).
        var measured = await MeasureAsync(new SimulatorOptions { HostLateness = HostLateness.Realistic, Seed = seed }, exchanges: 200);
        var latency = measured.ToProfile(new LatencyProfile());

        Assert.Equal(1000, measured.Host!.Count);
        Assert.InRange(latency.HostLatenessMs, 0.45, 0.5);
        Assert.InRange(latency.HostLatenessTailMs, 0.5, 5);
    }

    [Fact(Timeout = 30_000)]
    public async Task MeasureAsync_NeverLateHost_HostLatenessZero()
    {
        var latency = (await MeasureAsync(new SimulatorOptions(), exchanges: 20)).ToProfile(new LatencyProfile());

        Assert.Equal((0.0, 0.0), (latency.HostLatenessMs, latency.HostLatenessTailMs));
    }

    [Fact(Timeout = 30_000)]
    public async Task MeasureAsync_EachDevice_TimesItsExchangesAboveTheWireTime()
    {
        var measured = await MeasureAsync(new SimulatorOptions(), exchanges: 50);

        // Echo Data: two 6-byte frames at 9600 baud; "PING\n" and "OK PONG\n": 13 bytes.
        Assert.Equal(12.5, measured.X.WireMs, 9);
        Assert.Equal(130 / 9.6, measured.Gate.WireMs, 9);
        foreach (var trips in new[] { measured.X, measured.Y, measured.Gate })
        {
            Assert.Equal(50, trips.Count);
            Assert.InRange(trips.MinMs, trips.WireMs + 1.0, trips.MeanMs);
            Assert.InRange(trips.MaxMs, trips.MeanMs, trips.WireMs + 3.7);
        }

        Assert.Equal(100, measured.Stage.Count);
        Assert.Contains("device 1", measured.X.Device, StringComparison.Ordinal);
        Assert.Contains("device 2", measured.Y.Device, StringComparison.Ordinal);
    }

    [Fact(Timeout = 30_000)]
    public async Task MeasureAsync_SameSeed_SameFigures_OtherSeed_Others()
    {
        var first = await MeasureAsync(new SimulatorOptions { Seed = 5 }, exchanges: 40);
        var again = await MeasureAsync(new SimulatorOptions { Seed = 5 }, exchanges: 40);
        var other = await MeasureAsync(new SimulatorOptions { Seed = 6 }, exchanges: 40);

        Assert.Equal(first, again);
        Assert.NotEqual(first.X.MeanMs, other.X.MeanMs);
    }

    [Fact(Timeout = 30_000)]
    public async Task MeasureAsync_SlowerAdapters_AreMeasured_NotAssumed()
    {
        var options = new SimulatorOptions { AdapterLatency = new Jitter(4.0, 1.0), GateProcessing = new Jitter(2.0, 0.5) };
        var kept = new LatencyProfile { GateProcessingMs = 2.0, GateProcessingJitterMs = 0.5 };

        var latency = (await MeasureAsync(options)).ToProfile(kept);

        Assert.Equal(4.0, latency.StageMs, 0.1);
        Assert.Equal(1.0, latency.StageJitterMs, 0.1);
        Assert.Equal(4.0, latency.GateMs, 0.1);
        Assert.Equal(1.0, latency.GateJitterMs, 0.1);
        Assert.Equal(2.0, latency.GateProcessingMs);
    }
}
