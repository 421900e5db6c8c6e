using LaserEngrave.Core.Motion;

namespace LaserEngrave.Core.Tests.Motion;

public class TrapezoidProfileTests
{
    [Fact]
    public void Duration_LongMove_IsCruisePlusOneRamp()
    {
        var move = new TrapezoidProfile(distance: 100, maxSpeed: 10, acceleration: 5);
        // 2 s to reach 10, 20 units ramping in total, 80 at speed = 8 s.
        Assert.Equal(2, move.RampTime, 9);
        Assert.Equal(12, move.Duration, 9);
    }

    [Fact]
    public void Duration_ShortMove_IsTriangle()
    {
        var move = new TrapezoidProfile(distance: 5, maxSpeed: 10, acceleration: 5);
        Assert.Equal(2 * Math.Sqrt(1), move.Duration, 9);
        Assert.Equal(5, move.PeakSpeed, 9);
    }

    [Theory]
    [InlineData(100, 10, 5)]
    [InlineData(3, 10, 5)]
    [InlineData(1234.5, 7, 0.5)]
    public void TimeAt_InvertsDistanceAt(double distance, double speed, double acceleration)
    {
        var move = new TrapezoidProfile(distance, speed, acceleration);
        for (var i = 0; i <= 50; i++)
        {
            var t = move.Duration * i / 50;
            Assert.Equal(t, move.TimeAt(move.DistanceAt(t)), 6);
        }

        Assert.Equal(distance, move.DistanceAt(move.Duration), 9);
    }
}
