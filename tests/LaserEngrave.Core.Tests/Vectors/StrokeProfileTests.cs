using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Tests.Vectors;

/// <summary>The followed distance to a stroke's path: the same value as measuring every segment of the window, found with far fewer measurements.</summary>
public class StrokeProfileTests
{
    /// <summary>A spiral of tiny segments that folds back on itself, and a point that wanders around the ideal motion (as a lagging, overshooting axis model does).</summary>
    [Theory]
    [InlineData(0.8, 3.0)]
    [InlineData(8.0, 40.0)]
    [InlineData(0.3, 400.0)]
    public void DistanceFollowing_PointFollowedInSmallSteps_SameAsEverySegmentMeasured(double segment, double wander)
    {
        var points = new List<(double X, double Y)>();
        for (var i = 0; i < 6_000; i++)
        {
            var along = i * segment;
            var radius = 200 + (along / 50);
            var angle = along / radius;
            points.Add((radius * Math.Cos(angle), radius * Math.Sin(angle)));
        }

        var followed = new StrokeProfile(points, 1000, 5000);
        var measured = new StrokeProfile(points, 1000, 5000);
        var random = new Random(32);
        var (dx, dy) = (0.0, 0.0);
        for (var t = 0.0; t < followed.DurationSeconds; t += 0.00025)
        {
            var s = followed.DistanceAt(t);
            var (x, y) = followed.PointAt(s);
            (dx, dy) = (Math.Clamp(dx + ((random.NextDouble() - 0.5) * wander / 10), -wander, wander), Math.Clamp(dy + ((random.NextDouble() - 0.5) * wander / 10), -wander, wander));
            var window = 300.0;
            var from = Math.Max(0, s - window);
            var to = Math.Min(followed.Length, s + window);

            Assert.Equal(measured.DistanceToPath(x + dx, y + dy, from, to), followed.DistanceFollowing(x + dx, y + dy, from, to));
        }
    }
}
