using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Planning;

/// <summary>One dot of a <see cref="DotProgram"/>: the travel to it in device units, then its counted burst.</summary>
/// <param name="Index">The dot's place in the program, 0-based: a stop point's index is the first dot not fired.</param>
/// <param name="X">Absolute X target, whole microsteps.</param>
/// <param name="Y">Absolute Y target, whole microsteps.</param>
/// <param name="Row">Image row the dot burns on.</param>
/// <param name="SpeedData">Set Target Speed data of the move to the dot (the laser is off while the stage moves).</param>
/// <param name="Pulses">Pulses the gate fires at the dot (`BURST n f`).</param>
/// <param name="FrequencyHz">The burst's frequency, whole Hz.</param>
public readonly record struct DotStep(long Index, long X, long Y, int Row, int SpeedData, int Pulses, int FrequencyHz);

/// <summary>
/// A dot job's program: the acceleration and speed data both axes are set to, then for each dot in order its absolute
/// target and its counted burst, each step moved to and fired only once the one before has surely ended
/// (<see cref="DotTiming"/>). The executor (Devices/Execution/RunExecutor.Dots.cs) sends these steps, a stop point is an
/// index into them, a resume continues from it, and the estimate (<see cref="DotModeEstimate"/>) adds up the same steps.
/// </summary>
public sealed class DotProgram : PartProgram
{
    private readonly DotPlan _plan;

    internal DotProgram(DotPlan plan, ProcessSettings process, LaserGateProfile gate)
        : base(process, plan.Options.Strategy, plan.Geometry.MicrostepUm, gate)
    {
        _plan = plan;
    }

    /// <summary>The timing model every step follows.</summary>
    public DotTiming Timing => _plan.Timing;

    /// <summary>The dot plan it runs: its mask and its estimate.</summary>
    public DotPlan Plan => _plan;

    /// <summary>Set Acceleration data of both axes, set before the first dot.</summary>
    public int AccelerationData => Motion.AccelerationData;

    /// <summary>Set Target Speed data of both axes, set before the first dot; every move between dots runs at it.</summary>
    /// <remarks>The travel speed's (the burn speed's under a paper plan).</remarks>
    public int SpeedData => Motion.TravelSpeedData;

    /// <summary>The size of a microstep, µm.</summary>

    /// <summary>Every dot from index <paramref name="first"/> on (a stop point's), in order.</summary>
    public IEnumerable<DotStep> Steps(long first = 0)
    {
        ArgumentOutOfRangeException.ThrowIfNegative(first);
        return Enumerate(first);
    }

    /// <summary>The step from one dot to the next as the motion model has it: the move's commands, motion and replies, s.</summary>
    public double MoveSeconds(DotStep from, DotStep to) => Timing.StepSeconds(to.X - from.X, to.Y - from.Y, to.SpeedData);

    /// <summary>What the dots before <paramref name="first"/> took by the estimate, the start settings included, s.</summary>
    public double SecondsBefore(long first)
    {
        var before = Timing.StartSeconds;
        DotStep previous = default;
        foreach (var step in Steps().TakeWhile(s => s.Index < first))
        {
            before += (step.Index > 0 ? MoveSeconds(previous, step) : 0) + Timing.AtDotSeconds;
            previous = step;
        }

        return before;
    }

    private IEnumerable<DotStep> Enumerate(long first)
    {
        var index = first;
        foreach (var dot in _plan.Dots(first))
        {
            yield return new DotStep(index++, dot.X, dot.Y, dot.Row, SpeedData, Timing.PulsesPerDot, Timing.FrequencyHz);
        }
    }
}
