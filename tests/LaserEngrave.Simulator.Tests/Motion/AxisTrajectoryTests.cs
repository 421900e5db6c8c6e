using LaserEngrave.Simulator.Motion;

namespace LaserEngrave.Simulator.Tests.Motion;

public class AxisTrajectoryTests
{
    [Fact]
    public void PositionAt_BeforeAndAfterAMove_HoldsTheEnds()
    {
        var trajectory = new AxisTrajectory(100);
        trajectory.Replace(1, [new MotionSegment(1, 100, 50, 0, 2), MotionSegment.Hold(3, 200)]);

        Assert.Equal(100, trajectory.PositionAt(0.5));
        Assert.Equal(150, trajectory.PositionAt(2));
        Assert.Equal(200, trajectory.PositionAt(10));
        Assert.Equal(50, trajectory.VelocityAt(2));
        Assert.Equal(0, trajectory.VelocityAt(10));
    }

    [Fact]
    public void Replace_MidMove_CutsThePlanAndKeepsThePast()
    {
        var trajectory = new AxisTrajectory(0);
        trajectory.Replace(0, [new MotionSegment(0, 0, 100, 0, 10), MotionSegment.Hold(10, 1000)]);

        trajectory.Replace(4, [MotionSegment.Hold(4, 400)]);

        Assert.Equal(200, trajectory.PositionAt(2));
        Assert.Equal(400, trajectory.PositionAt(5));
        Assert.Equal(400, trajectory.PositionAt(20));
        Assert.Equal(4, trajectory.EndSeconds);
    }

    [Fact]
    public void Replace_SegmentStartingBeforeTheLast_Throws()
    {
        var trajectory = new AxisTrajectory(0);
        trajectory.Replace(5, [MotionSegment.Hold(5, 1)]);

        Assert.Throws<ArgumentException>(() => trajectory.Replace(6, [MotionSegment.Hold(4, 2)]));
    }
}
