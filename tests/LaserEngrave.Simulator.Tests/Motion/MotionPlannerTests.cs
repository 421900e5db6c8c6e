using LaserEngrave.Core.Motion;
using LaserEngrave.Simulator.Motion;

namespace LaserEngrave.Simulator.Tests.Motion;

public class MotionPlannerTests
{
    [Theory]
    [InlineData(0, 100_000, 18_750, 112_500)]
    [InlineData(50_000, 49_000, 18_750, 112_500)]
    [InlineData(10, 12, 40_000, 11_250)]
    public void Plan_FromRest_FollowsTrapezoidProfile(double from, double to, double speed, double acceleration)
    {
        var profile = new TrapezoidProfile(to - from, speed, acceleration);

        var plan = MotionPlanner.Plan(3.0, from, 0, to, speed, acceleration);
        var trajectory = Build(from, plan);

        Assert.Equal(3.0 + profile.Duration, plan[^1].StartSeconds, 9);
        for (var i = 0; i <= 40; i++)
        {
            var t = profile.Duration * i / 40;
            Assert.Equal(from + (Math.Sign(to - from) * profile.DistanceAt(t)), trajectory.PositionAt(3.0 + t), 6);
        }

        Assert.Equal(to, trajectory.PositionAt(1e9));
    }

    [Fact]
    public void Plan_ZeroDistance_IsOnlyAHold()
    {
        var plan = MotionPlanner.Plan(1, 500, 0, 500, 100, 100);

        Assert.Equal([MotionSegment.Hold(1, 500)], plan);
    }

    public static TheoryData<double, double, double> MovingStarts => new()
    {
        { 0, 10_000, 100_000 },      // moving towards the target, room to spare
        { 0, 10_000, 1_000 },        // towards it but too fast to stop in time: brake, come back
        { 0, -10_000, 100_000 },     // moving away: brake, turn round
        { 0, 30_000, 100_000 },      // faster than the new top speed: slow down first
        { 5_000, 2_000, 5_100 },     // towards a close target, just able to stop
    };

    [Theory]
    [MemberData(nameof(MovingStarts))]
    public void Plan_FromMoving_IsContinuousAndEndsAtRestOnTheTarget(double from, double velocity, double to)
    {
        const double speed = 18_750, acceleration = 112_500;

        var plan = MotionPlanner.Plan(0, from, velocity, to, speed, acceleration);

        Assert.Equal(from, plan[0].StartPosition, 9);
        Assert.Equal(velocity, plan[0].StartVelocity, 9);
        for (var i = 1; i < plan.Count; i++)
        {
            Assert.Equal(plan[i - 1].EndSeconds, plan[i].StartSeconds, 9);
            Assert.Equal(plan[i - 1].EndPosition, plan[i].StartPosition, 6);
            Assert.Equal(plan[i - 1].EndVelocity, plan[i].StartVelocity, 6);
        }

        Assert.All(plan, s => Assert.True(Math.Abs(s.Acceleration) <= acceleration + 1e-9));
        Assert.All(plan, s => Assert.True(Math.Abs(s.EndVelocity) <= Math.Max(speed, Math.Abs(velocity)) + 1e-6));
        Assert.Equal(0, plan[^1].EndVelocity, 9);
        Assert.Equal(to, plan[^1].EndPosition, 6);
    }

    [Fact]
    public void Stop_Moving_BrakesAtTheAccelerationAndRestsOnAWholeMicrostep()
    {
        var plan = MotionPlanner.Stop(2, 1000.3, -3000, 10_000);

        // v²/2a = 450 microsteps in 0.3 s.
        Assert.Equal(2.3, plan[^1].StartSeconds, 9);
        Assert.Equal(550, plan[^1].StartPosition);
        Assert.Equal(0, plan[^1].EndVelocity);
    }

    private static AxisTrajectory Build(double from, List<MotionSegment> plan)
    {
        var trajectory = new AxisTrajectory(from);
        trajectory.Replace(plan[0].StartSeconds, plan);
        return trajectory;
    }
}
