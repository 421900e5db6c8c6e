using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Vectors;

/// <summary>The travel to a stroke's run-up start with the laser off: Move Absolute of the axes that must move, replies awaited.</summary>
/// <param name="From">Where the model has the axes resting after the stroke before; null for the run's first travel, from wherever the stage stands (the positioning, not part of the estimate).</param>
/// <param name="To">The run-up's start, whole microsteps.</param>
/// <param name="SpeedData">Set Target Speed data of the travel.</param>
/// <param name="StreamedX">The stroke before streamed X: it is moved even when the model has it at the target already, since where it rests depends on when each of its commands arrived.</param>
/// <param name="StreamedY">As <paramref name="StreamedX"/>, for Y.</param>
public readonly record struct DrawingTravel(StagePoint? From, StagePoint To, int SpeedData, bool StreamedX, bool StreamedY);

/// <summary>One stroke of a <see cref="DrawingProgram"/>: the travel to its run-up, then its timed axis commands and laser edges.</summary>
/// <param name="Index">The stroke's place in the job, 0-based: a stop point's index is the stroke under way.</param>
/// <param name="LastOfPath">Whether the stroke ends its drawing path (a path split at a sharp corner is several strokes).</param>
/// <param name="Travel">The travel to the stroke's run-up start.</param>
/// <param name="Stroke">
/// The stroke in device units: each axis' Move At Constant Speed (signed speed data, <c>StageUnits.SignedSpeedData</c>),
/// stop and position query at the time it is to arrive, the position the query should see, the laser's switch-on and
/// switch-off times, and where the axes rest after it.
/// </param>
public sealed record DrawingStep(int Index, bool LastOfPath, DrawingTravel Travel, VectorStroke Stroke);

/// <summary>
/// A drawing's program: the acceleration and travel speed data both axes are set to, then per stroke the travel to its
/// run-up start and the stroke's commands by time, from a stop point on. The executor
/// (Devices/Execution/RunExecutor.Vector.cs) sends these steps, a stop point is a stroke's index, a resume continues
/// from it, and the estimate (<see cref="SecondsFrom"/>, <see cref="VectorSchedule.EstimatedSeconds"/>) adds up the same
/// steps by the motion model.
/// </summary>
public sealed class DrawingProgram : PartProgram
{
    // Time the host allows itself to react to a reply before acting on it (as TimedSwitching).
    private const double ReactionSeconds = 0.0005;

    private readonly IReadOnlyList<VectorStroke> _strokes;

    internal DrawingProgram(IReadOnlyList<VectorStroke> strokes, TimedSwitching timing)
        : base(timing.Process, PlanStrategy.Optimized, timing.MicrostepUm, timing.Profile.Gate)
    {
        _strokes = strokes;
        Timing = timing;
    }

    /// <summary>The timing model every step follows.</summary>
    public TimedSwitching Timing { get; }

    public override TimedSwitching? SwitchTiming => Timing;

    /// <summary>Set Acceleration data of both axes, set before the first stroke.</summary>
    public int AccelerationData => Motion.AccelerationData;

    /// <summary>Set Target Speed data of both axes, set before the first stroke; every travel runs at it.</summary>
    public int TravelSpeedData => Motion.TravelSpeedData;

    /// <summary>How many strokes the program has.</summary>
    public int StrokeCount => _strokes.Count;

    /// <summary>Setting acceleration and travel speed on both axes, one round trip each, s.</summary>
    public double SetupSeconds => 4 * (Timing.StageCommandSeconds + Timing.StageReplySeconds);

    /// <summary>The strokes from <paramref name="first"/> on (a stop point's), each with its travel; the first travel is the positioning.</summary>
    public IEnumerable<DrawingStep> Steps(int first = 0)
    {
        ArgumentOutOfRangeException.ThrowIfNegative(first);
        return Enumerate(first);
    }

    /// <summary>
    /// A travel's time from its write until the host has both replies and may write the next stroke (the positioning: 0,
    /// it is not part of the engraving).
    /// </summary>
    public double TravelSeconds(DrawingTravel travel)
    {
        if (travel.From is not { } from)
        {
            return 0;
        }

        var to = travel.To;
        long dx = Math.Abs(to.X - from.X), dy = Math.Abs(to.Y - from.Y);
        bool moveX = dx != 0 || travel.StreamedX, moveY = dy != 0 || travel.StreamedY;
        if (!moveX || !moveY)
        {
            return !moveX && !moveY ? ReactionSeconds : Timing.StageCommandSeconds + Timing.TravelSeconds(dx, dy) + Timing.StageReplySeconds + ReactionSeconds;
        }

        // X is written first, Y right behind it on the wire (a frame later); the replies queue one behind the other coming back.
        var frame = Timing.FrameSeconds;
        var xEnd = dx == 0 ? 0 : Timing.Travel(dx).Duration;
        var yEnd = frame + (dy == 0 ? 0 : Timing.Travel(dy).Duration);
        var firstReply = Math.Min(xEnd, yEnd) + frame;
        var last = Math.Max(Math.Max(xEnd, yEnd) + frame, firstReply + frame);
        return Timing.StageCommandSeconds + last + Timing.StageAdapterSeconds + ReactionSeconds;
    }

    /// <summary>The engraving's time from stroke <paramref name="first"/> on (a resumed run): the setup, each travel and stroke, the last switch-off, s.</summary>
    public double SecondsFrom(int first)
    {
        var total = SetupSeconds;
        foreach (var step in Steps(first))
        {
            // A travel is written when the stroke before reaches its NextArrivalSeconds, counted from the stroke's own first write.
            total += TravelSeconds(step.Travel);
            total += step.Stroke.NextArrivalSeconds;
        }

        return total + Timing.OffRoundTripSeconds;
    }

    private IEnumerable<DrawingStep> Enumerate(int first)
    {
        for (var k = first; k < _strokes.Count; k++)
        {
            var stroke = _strokes[k];
            var before = k == first ? null : _strokes[k - 1];
            var travel = new DrawingTravel(
                before?.RestEnd,
                stroke.RunUpStart,
                TravelSpeedData,
                before?.Streams(VectorAxis.X) ?? false,
                before?.Streams(VectorAxis.Y) ?? false);
            var lastOfPath = k + 1 >= _strokes.Count || _strokes[k + 1].PathIndex != stroke.PathIndex;
            yield return new DrawingStep(k, lastOfPath, travel, stroke);
        }
    }
}
