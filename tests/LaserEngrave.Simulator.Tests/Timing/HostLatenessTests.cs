using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Scheduling;

namespace LaserEngrave.Simulator.Tests.Timing;

/// <summary>The twin's model of a busy computer: the host wakes late from its timed waits, seeded, with tails.</summary>
public class HostLatenessTests
{
    [Fact(Timeout = 20_000)]
    public async Task PreciseDelay_HostLateness_EndsLateByTheDrawAndTheSameSeedGivesTheSameWaits()
    {
        async Task<double[]> WaitsAsync(int seed)
        {
            await using var machine = SimulatedMachine.CreateInProcess(LaserEngrave.Core.Geometry.MachineProfile.Default, new SimulatorOptions { Seed = seed, HostLateness = new HostLateness(0.5, 0.1, 5) });
            var time = machine.TimeProvider;
            return await machine.RunAsync(async () =>
            {
                var waits = new double[200];
                for (var i = 0; i < waits.Length; i++)
                {
                    var start = time.GetTimestamp();
                    await PreciseDelay.DelayAsync(time, TimeSpan.FromMilliseconds(10), CancellationToken.None);
                    waits[i] = time.GetElapsedTime(start).TotalMilliseconds;
                }

                return waits;
            });
        }

        var first = await WaitsAsync(3);
        var again = await WaitsAsync(3);

        Assert.Equal(first, again);
        Assert.All(first, w => Assert.InRange(w, 10, 15 + 1e-9));
        Assert.Contains(first, w => w > 10.5);
        Assert.InRange(first.Count(w => w <= 10.5), 150, 199);
    }

    [Fact(Timeout = 20_000)]
    public async Task PreciseDelay_NoHostLateness_EndsOnTime()
    {
        await using var machine = SimulatedMachine.CreateInProcess(LaserEngrave.Core.Geometry.MachineProfile.Default, new SimulatorOptions());
        var time = machine.TimeProvider;

        var waited = await machine.RunAsync(async () =>
        {
            var start = time.GetTimestamp();
            await PreciseDelay.DelayAsync(time, TimeSpan.FromMilliseconds(10), CancellationToken.None);
            return time.GetElapsedTime(start).TotalMilliseconds;
        });

        Assert.Equal(10, waited, 9);
    }

    [Theory]
    [InlineData("""{ "hostLateness": { "typicalMs": 0.5, "tailProbability": 0.01, "tailMs": 5 } }""", null)]
    [InlineData("""{ "hostLateness": { "typicalMs": -1, "tailProbability": 0.01, "tailMs": 5 } }""", "hostLateness must have")]
    [InlineData("""{ "hostLateness": { "typicalMs": 0.5, "tailProbability": 2, "tailMs": 5 } }""", "tailProbability from 0 to 1")]
    public void OptionsFile_HostLateness_ReadOrRefusedNamingTheField(string json, string? fragment)
    {
        var path = Path.Combine(Path.GetTempPath(), $"sim-{Guid.NewGuid():N}.json");
        try
        {
            File.WriteAllText(path, json);
            if (fragment is null)
            {
                Assert.Equal(new HostLateness(0.5, 0.01, 5), SimulatorOptionsFile.Load(path, new SimulatorOptions()).HostLateness);
            }
            else
            {
                var ex = Assert.Throws<InvalidDataException>(() => SimulatorOptionsFile.Load(path, new SimulatorOptions()));
                Assert.Contains(fragment, ex.Message, StringComparison.Ordinal);
            }
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Theory]
    [InlineData("""{ "seed": 3 }""", -1, 0, 0)]
    [InlineData("""{ "hostLateness": { "typicalMs": 0, "tailProbability": 0, "tailMs": 0 } }""", 0, 0, 0)]
    [InlineData("""{ "hostLateness": { "typicalMs": 2, "tailProbability": 0.05, "tailMs": 14 } }""", 2, 0.05, 14)]
    public void FrontEnd_RealisticByDefault_TheFileOverridesItEitherWay(string json, double typicalMs, double tailProbability, double tailMs)
    {
        var path = Path.Combine(Path.GetTempPath(), $"sim-{Guid.NewGuid():N}.json");
        try
        {
            File.WriteAllText(path, json);

            Assert.Equal(HostLateness.Realistic, SimulatorOptions.FrontEnd.HostLateness);
            Assert.True(new SimulatorOptions().HostLateness.IsNone, "the library's default stays never late, for tests of the protocol alone");
            Assert.Equal(typicalMs < 0 ? HostLateness.Realistic : new HostLateness(typicalMs, tailProbability, tailMs), SimulatorOptionsFile.Load(path, SimulatorOptions.FrontEnd).HostLateness);
        }
        finally
        {
            File.Delete(path);
        }
    }
}
