using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Vectors;

/// <summary>A vector job's strokes as the executor runs them, and the time they take by the same model.</summary>
public sealed class VectorSchedule
{
    // Time the host allows itself to react to a reply before acting on it (as TimedSwitching).
    private const double ReactionSeconds = 0.0005;

    internal VectorSchedule(IReadOnlyList<VectorStroke> strokes, TimedSwitching timing, bool fitsTravel, IReadOnlyList<string> warnings, VectorMotionOptions options)
    {
        Strokes = strokes;
        Timing = timing;
        FitsTravel = fitsTravel;
        Warnings = warnings;
        Options = options;
        EstimatedSeconds = SecondsFrom(0);
        PredictedDeviationUm = strokes.Count == 0 ? 0 : strokes.Max(s => s.PredictedDeviationUm);
    }

    public IReadOnlyList<VectorStroke> Strokes { get; }

    public TimedSwitching Timing { get; }

    public VectorMotionOptions Options { get; }

    /// <summary>Whether every stroke, with its run-up and run-out, stays inside the travel (away from the ends, where a constant-speed move brakes).</summary>
    public bool FitsTravel { get; }

    public IReadOnlyList<string> Warnings { get; }

    /// <summary>The engraving's time, as the executor does it: from setting the axes' acceleration and speed to the last switch-off, s.</summary>
    public double EstimatedSeconds { get; }

    /// <summary>The model's largest distance from the path with the laser on, over every stroke, µm.</summary>
    public double PredictedDeviationUm { get; }

    /// <summary>Setting acceleration and travel speed on both axes, one round trip each.</summary>
    public double SetupSeconds => 4 * (Timing.StageCommandSeconds + Timing.StageReplySeconds);

    /// <summary>From the host's write of a stroke's first command to its travel's write (the next stroke's run-up start reached or not).</summary>
    public static double StrokeSeconds(VectorStroke stroke) => stroke.NextArrivalSeconds;

    /// <summary>
    /// A travel's time from its write until the host has both replies and may write the next stroke: an axis the stroke
    /// before streamed is moved even when the model has it at the run-up's start already (<see cref="VectorStroke.Streams"/>).
    /// </summary>
    public double TravelSeconds(VectorStroke from, StagePoint to)
    {
        ArgumentNullException.ThrowIfNull(from);
        long dx = Math.Abs(to.X - from.RestEnd.X), dy = Math.Abs(to.Y - from.RestEnd.Y);
        bool moveX = dx != 0 || from.Streams(VectorAxis.X), moveY = dy != 0 || from.Streams(VectorAxis.Y);
        if (!moveX || !moveY)
        {
            return !moveX && !moveY ? ReactionSeconds : Timing.StageCommandSeconds + Timing.TravelSeconds(dx, dy) + Timing.StageReplySeconds + ReactionSeconds;
        }

        // X is written first, Y right behind it on the wire (a frame later); the replies queue one behind the other coming back.
        var frame = Timing.FrameSeconds;
        var xEnd = dx == 0 ? 0 : Timing.Travel(dx).Duration;
        var yEnd = frame + (dy == 0 ? 0 : Timing.Travel(dy).Duration);
        var first = Math.Min(xEnd, yEnd) + frame;
        var last = Math.Max(Math.Max(xEnd, yEnd) + frame, first + frame);
        return Timing.StageCommandSeconds + last + Timing.StageAdapterSeconds + ReactionSeconds;
    }

    /// <summary>The time of the strokes from <paramref name="first"/> on (a resumed run), with the setup and the last switch-off.</summary>
    public double SecondsFrom(int first)
    {
        var total = SetupSeconds;
        for (var k = first; k < Strokes.Count; k++)
        {
            var stroke = Strokes[k];
            total += stroke.NextArrivalSeconds;
            if (k + 1 < Strokes.Count)
            {
                // The travel is written when the stroke's NextArrivalSeconds is reached, counted from its own first write.
                total += TravelSeconds(stroke, Strokes[k + 1].RunUpStart);
            }
        }

        return total + Timing.OffRoundTripSeconds;
    }
}
