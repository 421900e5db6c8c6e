using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Vectors;

/// <summary>A vector job's strokes as the executor runs them, and the time they take by the same model.</summary>
public sealed class VectorSchedule
{
    private readonly DrawingProgram _program;

    internal VectorSchedule(IReadOnlyList<VectorStroke> strokes, TimedSwitching timing, bool fitsTravel, IReadOnlyList<string> warnings, VectorMotionOptions options)
    {
        Strokes = strokes;
        Timing = timing;
        FitsTravel = fitsTravel;
        Warnings = warnings;
        Options = options;
        _program = new DrawingProgram(strokes, timing);
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
    public double SetupSeconds => _program.SetupSeconds;

    /// <summary>From the host's write of a stroke's first command to its travel's write (the next stroke's run-up start reached or not).</summary>
    public static double StrokeSeconds(VectorStroke stroke) => stroke.NextArrivalSeconds;

    /// <summary>The device-unit program of these strokes: per stroke the travel to it and its commands (what is sent, estimated and resumed).</summary>
    public DrawingProgram Program() => _program;

    /// <summary>The time of the strokes from <paramref name="first"/> on (a resumed run), with the setup and the last switch-off: the program's steps added up.</summary>
    public double SecondsFrom(int first) => _program.SecondsFrom(first);
}
