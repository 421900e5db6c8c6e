using LaserEngrave.Core.Motion;

namespace LaserEngrave.Simulator.Motion;

/// <summary>Plans an axis' motion to a target as constant-acceleration segments, from rest or from a moving start.</summary>
internal static class MotionPlanner
{
    /// <summary>Below this a distance or speed counts as zero (microsteps, microsteps/s).</summary>
    private const double Epsilon = 1e-9;

    /// <summary>
    /// Segments that take the axis from <paramref name="position"/> moving at <paramref name="velocity"/> to rest at
    /// <paramref name="target"/>, never faster than <paramref name="maxSpeed"/>; the last one holds the exact target.
    /// </summary>
    /// <remarks>
    /// From rest this is exactly <see cref="TrapezoidProfile"/> (the estimator's model). When a move pre-empts another,
    /// the axis first brakes if it is heading away or cannot stop in time, then moves to the target.
    /// </remarks>
    public static List<MotionSegment> Plan(double startSeconds, double position, double velocity, double target, double maxSpeed, double acceleration)
    {
        var plan = new List<MotionSegment>(5);
        var t = startSeconds;
        var x = position;
        var distance = Math.Abs(target - x);
        var direction = Math.Sign(target - x);
        var speed = Math.Abs(velocity);

        if (speed > Epsilon && (Math.Sign(velocity) != direction || speed * speed / (2 * acceleration) > distance + Epsilon))
        {
            var brake = new MotionSegment(t, x, velocity, -Math.Sign(velocity) * acceleration, speed / acceleration);
            plan.Add(brake);
            t = brake.EndSeconds;
            x = brake.EndPosition;
            speed = 0;
            distance = Math.Abs(target - x);
            direction = Math.Sign(target - x);
        }

        if (distance > Epsilon)
        {
            if (speed <= Epsilon)
            {
                AddFromRest(plan, ref t, x, direction, new TrapezoidProfile(distance, maxSpeed, acceleration));
            }
            else
            {
                AddFromMoving(plan, ref t, x, direction, speed, distance, maxSpeed, acceleration);
            }
        }

        plan.Add(MotionSegment.Hold(t, target));
        return plan;
    }

    /// <summary>Braking to a stop as fast as the acceleration allows; the axis then rests at the nearest whole microstep.</summary>
    public static List<MotionSegment> Stop(double startSeconds, double position, double velocity, double acceleration)
    {
        var plan = new List<MotionSegment>(2);
        var speed = Math.Abs(velocity);
        var t = startSeconds;
        var x = position;
        if (speed > Epsilon)
        {
            var brake = new MotionSegment(t, x, velocity, -Math.Sign(velocity) * acceleration, speed / acceleration);
            plan.Add(brake);
            t = brake.EndSeconds;
            x = brake.EndPosition;
        }

        plan.Add(MotionSegment.Hold(t, Math.Round(x, MidpointRounding.AwayFromZero)));
        return plan;
    }

    private static void AddFromRest(List<MotionSegment> plan, ref double t, double x, int direction, TrapezoidProfile profile)
    {
        var a = direction * profile.Acceleration;
        var peak = direction * profile.PeakSpeed;
        Add(plan, ref t, ref x, 0, a, profile.RampTime);
        Add(plan, ref t, ref x, peak, 0, profile.CruiseTime);
        Add(plan, ref t, ref x, peak, -a, profile.RampTime);
    }

    private static void AddFromMoving(List<MotionSegment> plan, ref double t, double x, int direction, double speed, double distance, double maxSpeed, double acceleration)
    {
        // Change speed towards the peak, cruise, brake: the ramps take (peak² - speed²)/2a and peak²/2a.
        var peak = Math.Min(maxSpeed, Math.Sqrt((acceleration * distance) + (speed * speed / 2)));
        var rampTime = Math.Abs(peak - speed) / acceleration;
        var rampDistance = Math.Abs((peak * peak) - (speed * speed)) / (2 * acceleration);
        var brakeDistance = peak * peak / (2 * acceleration);
        var cruiseTime = Math.Max(0, distance - rampDistance - brakeDistance) / peak;
        Add(plan, ref t, ref x, direction * speed, direction * Math.Sign(peak - speed) * acceleration, rampTime);
        Add(plan, ref t, ref x, direction * peak, 0, cruiseTime);
        Add(plan, ref t, ref x, direction * peak, -direction * acceleration, peak / acceleration);
    }

    private static void Add(List<MotionSegment> plan, ref double t, ref double x, double velocity, double acceleration, double duration)
    {
        if (duration <= 0)
        {
            return;
        }

        var segment = new MotionSegment(t, x, velocity, acceleration, duration);
        plan.Add(segment);
        t = segment.EndSeconds;
        x = segment.EndPosition;
    }
}
