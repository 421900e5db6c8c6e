namespace LaserEngrave.Core.Vectors;

/// <summary>
/// One axis as the Zaber device moves it under constant-speed commands: its velocity ramps at the acceleration to the
/// commanded speed and holds it; a stop brakes to rest on the nearest whole microstep (the simulator's and the
/// estimator's model, docs/simulator.md).
/// </summary>
internal struct AxisModel(double position, double acceleration)
{
    public double Position { get; private set; } = position;

    public double Velocity { get; private set; }

    /// <summary>The speed commanded, microsteps/s.</summary>
    public double Command { get; private set; }

    public double Time { get; private set; }

    public bool Stopping { get; private set; }

    public readonly bool AtRest => Velocity == 0 && Command == 0;

    /// <summary>When the axis reaches its commanded speed (or rest).</summary>
    public readonly double SettledSeconds => Time + (Math.Abs(Command - Velocity) / acceleration);

    public void Apply(AxisCommand command)
    {
        AdvanceTo(command.AtSeconds);
        switch (command.Kind)
        {
            case AxisCommandKind.Speed:
                Command = Geometry.StageUnits.SpeedMicrostepsPerS(command.SpeedData);
                Stopping = false;
                break;
            case AxisCommandKind.Stop:
                Command = 0;
                Stopping = true;
                break;
        }
    }

    public void AdvanceTo(double seconds)
    {
        var dt = seconds - Time;
        if (dt <= 0)
        {
            return;
        }

        Time = seconds;
        var dv = Command - Velocity;
        if (dv == 0)
        {
            Position += Velocity * dt;
            return;
        }

        var a = Math.Sign(dv) * acceleration;
        var ramp = Math.Abs(dv) / acceleration;
        if (dt < ramp)
        {
            Position += (Velocity * dt) + (0.5 * a * dt * dt);
            Velocity += a * dt;
            return;
        }

        Position += (Velocity * ramp) + (0.5 * a * ramp * ramp) + (Command * (dt - ramp));
        Velocity = Command;
        if (Stopping && Command == 0)
        {
            Position = Math.Round(Position, MidpointRounding.AwayFromZero);
            Stopping = false;
        }
    }

    /// <summary>
    /// The speed to command now so that the axis is at <paramref name="target"/> after <paramref name="seconds"/>, given
    /// that it ramps there from its present velocity (as far as the acceleration allows in that time).
    /// </summary>
    public readonly double SpeedToReach(double target, double seconds)
    {
        var w = Velocity;
        var g = target - Position - (w * seconds);
        var most = acceleration * seconds * seconds / 2;
        if (g >= most)
        {
            return w + (acceleration * seconds);
        }

        if (g <= -most)
        {
            return w - (acceleration * seconds);
        }

        var ah = acceleration * seconds;
        var e = g >= 0 ? ah - Math.Sqrt((ah * ah) - (2 * acceleration * g)) : -(ah - Math.Sqrt((ah * ah) + (2 * acceleration * g)));
        return w + e;
    }
}
