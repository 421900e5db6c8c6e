using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Process;

public class DotModeEstimateTests
{
    [Fact]
    public void For_TenPulsesAtOneKilohertz_DwellIsTenMsPlusSettle()
    {
        var mask = new BitMask(20, 10);
        for (var x = 0; x < 20; x += 2)
        {
            for (var y = 0; y < 10; y++)
            {
                mask[x, y] = true;
            }
        }

        // 100 µm pitch = 1000 microsteps of 0.1 µm; 0.9375 mm/s = 1000 speed units exactly; 11.25 mm/s² = 10 units exactly.
        var geometry = new JobGeometry(20, 10, 1000, 0, 0, 0.1, 1_000_000, 1_000_000);
        var process = ProcessSettings.Default with
        {
            Mode = PlanMode.Dots,
            PulsesPerDot = 10,
            LaserFrequencyHz = 1000,
            DotSettleMs = 5,
            BurnSpeedMmPerS = 0.9375,
            AccelerationMmPerS2 = 11.25,
        };

        var estimate = DotModeEstimate.For(mask, geometry, process);

        Assert.Equal(100, estimate.Dots);
        Assert.Equal(0.010, estimate.BurstSeconds, 12);
        Assert.Equal(0.015, estimate.DwellSeconds, 12);

        // Step: ramps to 9375 µsteps/s in 1/12 s over 390.625 µsteps each way, cruises the other 218.75 µsteps: 0.19 s.
        Assert.Equal(0.19, estimate.StepSeconds, 9);

        // Move Absolute and reply: 12 bytes; "BURST 10 1000\n" and "OK BURST 10\n": 26 bytes; 10 bits each at 9600 baud.
        Assert.Equal((12 + 26) * 10 / 9600.0, estimate.CommandSeconds, 12);
        Assert.Equal(100 * (0.19 + (38 * 10 / 9600.0) + 0.015), estimate.DotsSeconds, 9);
    }

    [Fact]
    public void Validate_ZeroPulsesPerDot_Throws()
    {
        Assert.Throws<PlanException>(() => (ProcessSettings.Default with { PulsesPerDot = 0 }).Validate());
    }
}
