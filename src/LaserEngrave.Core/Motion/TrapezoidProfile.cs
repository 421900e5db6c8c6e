namespace LaserEngrave.Core.Motion;

/// <summary>A point-to-point move that accelerates, cruises and decelerates symmetrically (a triangle when short).</summary>
/// <remarks>Shared by the estimator and the simulator so that the two agree by construction.</remarks>
public readonly record struct TrapezoidProfile
{
    public TrapezoidProfile(double distance, double maxSpeed, double acceleration)
    {
        if (maxSpeed <= 0 || acceleration <= 0)
        {
            throw new ArgumentOutOfRangeException(nameof(maxSpeed), "speed and acceleration must be above 0");
        }

        Distance = Math.Abs(distance);
        Acceleration = acceleration;
        var rampDistance = maxSpeed * maxSpeed / acceleration;
        if (Distance >= rampDistance)
        {
            PeakSpeed = maxSpeed;
            RampTime = maxSpeed / acceleration;
            CruiseTime = (Distance - rampDistance) / maxSpeed;
        }
        else
        {
            PeakSpeed = Math.Sqrt(Distance * acceleration);
            RampTime = PeakSpeed / acceleration;
            CruiseTime = 0;
        }
    }

    /// <summary>Length of the move (always positive), in the caller's distance unit.</summary>
    public double Distance { get; }

    public double Acceleration { get; }

    /// <summary>Highest speed reached.</summary>
    public double PeakSpeed { get; }

    /// <summary>Time spent accelerating (and, equally, decelerating).</summary>
    public double RampTime { get; }

    public double CruiseTime { get; }

    public double Duration => (2 * RampTime) + CruiseTime;

    /// <summary>Distance covered after <paramref name="t"/> seconds.</summary>
    public double DistanceAt(double t)
    {
        if (t <= 0)
        {
            return 0;
        }

        if (t >= Duration)
        {
            return Distance;
        }

        var rampDistance = 0.5 * Acceleration * RampTime * RampTime;
        if (t < RampTime)
        {
            return 0.5 * Acceleration * t * t;
        }

        if (t < RampTime + CruiseTime)
        {
            return rampDistance + (PeakSpeed * (t - RampTime));
        }

        var left = Duration - t;
        return Distance - (0.5 * Acceleration * left * left);
    }

    /// <summary>Time at which <paramref name="d"/> has been covered (the inverse of <see cref="DistanceAt"/>).</summary>
    public double TimeAt(double d)
    {
        if (d <= 0)
        {
            return 0;
        }

        if (d >= Distance)
        {
            return Duration;
        }

        var rampDistance = 0.5 * Acceleration * RampTime * RampTime;
        if (d < rampDistance)
        {
            return Math.Sqrt(2 * d / Acceleration);
        }

        if (d <= Distance - rampDistance)
        {
            return RampTime + ((d - rampDistance) / PeakSpeed);
        }

        return Duration - Math.Sqrt(2 * (Distance - d) / Acceleration);
    }
}
