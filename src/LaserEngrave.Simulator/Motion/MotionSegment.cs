namespace LaserEngrave.Simulator.Motion;

/// <summary>A stretch of constant acceleration of one axis, in microsteps and seconds of simulation time.</summary>
/// <remarks>After <see cref="EndSeconds"/> the axis holds the end position until the next segment starts.</remarks>
/// <param name="StartSeconds">When the segment begins.</param>
/// <param name="StartPosition">Position at the start, microsteps.</param>
/// <param name="StartVelocity">Signed velocity at the start, microsteps/s.</param>
/// <param name="Acceleration">Signed acceleration, microsteps/s².</param>
/// <param name="DurationSeconds">How long the acceleration lasts (0 for a hold).</param>
public readonly record struct MotionSegment(
    double StartSeconds,
    double StartPosition,
    double StartVelocity,
    double Acceleration,
    double DurationSeconds)
{
    public double EndSeconds => StartSeconds + DurationSeconds;

    public double EndPosition => PositionAt(EndSeconds);

    public double EndVelocity => StartVelocity + (Acceleration * DurationSeconds);

    /// <summary>The axis standing at <paramref name="position"/> from <paramref name="startSeconds"/> on.</summary>
    public static MotionSegment Hold(double startSeconds, double position) => new(startSeconds, position, 0, 0, 0);

    public double PositionAt(double seconds)
    {
        var t = Math.Clamp(seconds - StartSeconds, 0, DurationSeconds);
        return StartPosition + (StartVelocity * t) + (0.5 * Acceleration * t * t);
    }

    /// <summary>Velocity at <paramref name="seconds"/>; 0 once the segment is over (every plan ends at rest).</summary>
    public double VelocityAt(double seconds)
    {
        var t = seconds - StartSeconds;
        return t < 0 || t >= DurationSeconds ? 0 : StartVelocity + (Acceleration * t);
    }
}
