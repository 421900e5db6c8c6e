using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Programs;

/// <summary>A dot job's program: each dot's absolute target, speed data and burst in order, from a stop point, and the estimate over it.</summary>
public class DotProgramTests
{
    // 1000 microsteps a pixel of 0.1 µm, origin 0: pixel c spans [1000 c, 1000 (c + 1)), row r burns along y = 1000 r + 500.
    private static readonly JobGeometry Geometry = new(4, 3, 1000, 0, 0, 0.1, 1_000_000, 1_000_000);

    private static DotPlan Plan(PlanStrategy strategy = PlanStrategy.Optimized)
    {
        var mask = new BitMask(4, 3);
        foreach (var (x, y) in new[] { (0, 0), (1, 0), (3, 0), (1, 2), (2, 2) })
        {
            mask[x, y] = true;
        }

        return new DotPlan(
            mask,
            Geometry,
            ProcessSettings.Default with { Mode = PlanMode.Dots, PulsesPerDot = 3 },
            MachineProfile.Default,
            new PlanOptions { Strategy = strategy });
    }

    [Fact]
    public void Steps_SmallPlan_EachDotsTargetSpeedDataAndBurstInOrder()
    {
        var program = Plan().Program();

        // Travel 4 mm/s at 0.1 µm a microstep: 40 000 microsteps/s, 4267 x 9.375; acceleration 50 mm/s²: 44 x 11 250.
        Assert.Equal(
            [
                new DotStep(0, 500, 500, 0, 4267, 3, 1000),
                new DotStep(1, 1500, 500, 0, 4267, 3, 1000),
                new DotStep(2, 3500, 500, 0, 4267, 3, 1000),
                new DotStep(3, 2500, 2500, 2, 4267, 3, 1000),
                new DotStep(4, 1500, 2500, 2, 4267, 3, 1000),
            ],
            program.Steps());
        Assert.Equal((4267, 44), (program.SpeedData, program.AccelerationData));
    }

    [Fact]
    public void Steps_PaperPlan_MovesAtTheBurnSpeedAsTheExecutorAlwaysHas()
    {
        // The executor sets the axes to the travel speed of the plan's strategy: the burn speed (1 mm/s) under paper.
        var program = Plan(PlanStrategy.Paper).Program();

        Assert.All(program.Steps(), s => Assert.Equal(1067, s.SpeedData));
    }

    [Fact]
    public void Steps_FromAStopPoint_TheSameStepsFromThere()
    {
        var program = Plan().Program();

        Assert.Equal(program.Steps().Skip(3), program.Steps(3));
        Assert.Empty(program.Steps(5));
        Assert.Throws<ArgumentOutOfRangeException>(() => program.Steps(-1));
    }

    [Fact]
    public void SecondsBefore_EveryStopPoint_TheEstimatesStartStepsAndDotsBeforeIt()
    {
        var plan = Plan();
        var program = plan.Program();
        var t = program.Timing;
        var steps = program.Steps().ToList();

        Assert.Equal(t.StartSeconds, program.SecondsBefore(0), 12);
        Assert.Equal(t.StartSeconds + t.AtDotSeconds + program.MoveSeconds(steps[0], steps[1]) + t.AtDotSeconds, program.SecondsBefore(2), 12);

        // All of them: the estimate's whole engraving but the final switch-off.
        Assert.Equal(plan.Estimate.TotalSeconds - t.OffRoundTripSeconds, program.SecondsBefore(5), 9);
    }

    [Fact]
    public void Estimate_OverTheProgram_TheFiguresItAddsUp()
    {
        var plan = Plan();
        var estimate = DotModeEstimate.For(plan.Program());

        Assert.Equal(plan.Estimate, estimate);
        Assert.Equal(5, estimate.Dots);

        // Between the dots: 1000, 2000, then (-1000, 2000) and 1000 microsteps of 0.1 µm.
        Assert.Equal((1000 + 2000 + Math.Sqrt(5e6) + 1000) * 1e-4, estimate.TravelLengthMm, 12);
    }
}
