using System.Globalization;
using System.Runtime.CompilerServices;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Motion;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Core.Planning;

/// <summary>Estimates how long the executor takes for a sequence of moves by replaying its protocol step by step.</summary>
/// <remarks>
/// The model, in the executor's order (PREAMBLE "How the executor drives the machine"):
/// <list type="number">
/// <item>Start: Set Acceleration and Set Target Speed (the travel speed of the strategy) on each axis, each a Zaber round trip.</item>
/// <item>Laser: before a burn with the laser off, the frequency command and its reply; before anything else with the laser
/// on, the off command and its reply. Each line takes its length in bytes (terminator included) at the gate's baud rate, 10
/// bits per byte (8N1); the replies are the documented ones, "OK FREQ f" and "OK FREQ 0" (docs/laser-gate-protocol.md).</item>
/// <item>Speed: on each axis that moves, Set Target Speed and its reply when the axis' speed data differ from what the move needs.</item>
/// <item>Motion: per moving axis, Move Absolute sent and its completion reply (two 6-byte frames) plus the trapezoid over the
/// microstep distance at the quantised Zaber speed and acceleration; when both axes move, the longer of the two.</item>
/// <item>End: the laser switched off if it is still on.</item>
/// </list>
/// The executor (Devices/Execution/RunExecutor) sends a switch-off before the speed changes and a switch-on after them,
/// so the laser never stands still while a speed is set; the order does not change the time, which is a sum.
/// Device and gate processing time, keepalives and the time to reach the plan's first position are not modelled
/// (docs/execution.md compares the estimate with simulated runs: within 0.3 % on the samples).
/// </remarks>
public sealed class PlanEstimator
{

    private readonly PlanStrategy _strategy;
    private readonly double _roundTripSeconds;
    private readonly double _laserOnSeconds;
    private readonly double _laserOffSeconds;
    private readonly double _accelerationMicrostepsPerS2;
    private readonly int _burnSpeedData;
    private readonly int _travelSpeedData;
    private readonly TimedSwitching? _timing;
    private int _xSpeedData;
    private int _ySpeedData;

    // Timed switching: the motion model the strokes and travels are timed by.
    private MotionTimeline? _timeline;

    /// <param name="process">Speeds, acceleration, frequency and baud rates.</param>
    /// <param name="strategy">The plan's strategy.</param>
    /// <param name="microstepUm">The stage's microstep.</param>
    /// <param name="gate">The gate's command strings (default: <see cref="LaserGateProfile"/>'s defaults).</param>
    /// <param name="timing">For an optimized plan made with timed switching: the model the executor runs it by (docs/execution.md).</param>
    public PlanEstimator(ProcessSettings process, PlanStrategy strategy, double microstepUm, LaserGateProfile? gate = null, TimedSwitching? timing = null)
    {
        ArgumentNullException.ThrowIfNull(process);
        gate ??= new LaserGateProfile();
        _strategy = strategy;

        _roundTripSeconds = 2 * ZaberFrame.Length * SerialLine.BitsPerByte / process.StageBaudRate;
        var gateByteSeconds = SerialLine.BitsPerByte / process.GateBaudRate;
        var onCommand = Line(gate, gate.FrequencyCommand, process.LaserFrequencyWholeHz);
        var onReply = gate.AckPrefix + " " + Line(gate, gate.FrequencyCommand, process.LaserFrequencyWholeHz);
        var offCommand = gate.OffCommand + gate.LineTerminator;
        var offReply = gate.AckPrefix + " " + Line(gate, gate.FrequencyCommand, 0);
        _laserOnSeconds = (onCommand.Length + onReply.Length) * gateByteSeconds;
        _laserOffSeconds = (offCommand.Length + offReply.Length) * gateByteSeconds;

        var motion = MotionData.Of(process, strategy, microstepUm);
        _burnSpeedData = motion.BurnSpeedData;
        _travelSpeedData = motion.TravelSpeedData;
        _accelerationMicrostepsPerS2 = StageUnits.AccelerationMicrostepsPerS2(motion.AccelerationData);

        _xSpeedData = _travelSpeedData;
        _ySpeedData = _travelSpeedData;
        _timing = strategy == PlanStrategy.Optimized ? timing : null;
        StartSeconds = 4 * _roundTripSeconds;
        ElapsedSeconds = StartSeconds;
    }

    /// <summary>Time for the start: acceleration and speed set on both axes.</summary>
    public double StartSeconds { get; }

    /// <summary>Time so far: the start plus every move added (and the final switch-off once <see cref="Finish"/> ran).</summary>
    public double ElapsedSeconds { get; private set; }

    public bool LaserOn { get; private set; }

    public long LaserSwitches { get; private set; }

    public long SpeedChanges { get; private set; }

    /// <summary>An estimator that interprets <paramref name="program"/>'s steps against its motion model.</summary>
    public PlanEstimator(RasterProgram program)
        : this(Checked(program).Process, program.Strategy, program.MicrostepUm, program.Gate, program.Timing)
    {
    }

    /// <summary>Advances over one move run step by step (the laser on for a burn, the strategy's speed); returns its time.</summary>
    /// <exception cref="InvalidOperationException">The estimator times strokes (a timed program): give it the program's steps.</exception>
    public double Add(in Move move)
    {
        if (_timing is not null)
        {
            throw new InvalidOperationException("a timed plan is estimated from its program's strokes and travels (RasterProgram)");
        }

        var speedData = _strategy == PlanStrategy.Optimized && move.Kind == MoveKind.Travel ? _travelSpeedData : _burnSpeedData;
        return Move(new MoveStep(move.Kind == MoveKind.Burn, move.X1, move.Y1, speedData, move, 0));
    }

    /// <summary>Advances over a plain move of a step-by-step program; returns its time (laser command, speed changes and motion).</summary>
    [MethodImpl(HotPath.Optimized)]
    public double Move(in MoveStep step)
    {
        var seconds = 0.0;
        if (step.LaserOn)
        {
            if (!LaserOn)
            {
                seconds += _laserOnSeconds;
                LaserOn = true;
                LaserSwitches++;
            }
        }
        else if (LaserOn)
        {
            seconds += _laserOffSeconds;
            LaserOn = false;
            LaserSwitches++;
        }

        var speedData = step.SpeedData;
        var dx = step.Move.LengthX;
        var dy = step.Move.LengthY;
        var motion = 0.0;
        if (dx != 0)
        {
            seconds += SetSpeed(ref _xSpeedData, speedData);
            motion = AxisSeconds(dx, speedData);
        }

        if (dy != 0)
        {
            seconds += SetSpeed(ref _ySpeedData, speedData);
            motion = Math.Max(motion, AxisSeconds(dy, speedData));
        }

        seconds += motion;
        ElapsedSeconds += seconds;
        return seconds;
    }

    /// <summary>Advances over a travel of a timed program: a stop-go move of one or both axes on the motion model; returns its time.</summary>
    [MethodImpl(HotPath.Optimized)]
    public double Travel(in TravelStep step)
    {
        var timeline = Timeline();
        var before = ElapsedSeconds;
        if (LaserOn)
        {
            LaserOn = false;
            LaserSwitches++;
        }

        var speed = timeline.XSpeedData;
        timeline.Travel(step.Move.LengthX, step.Move.LengthY);
        SpeedChanges += speed != timeline.XSpeedData ? 1 : 0;
        ElapsedSeconds = timeline.End;
        return ElapsedSeconds - before;
    }

    /// <summary>
    /// Advances over a stroke of a timed program: one move from rest to rest at the burn speed over its run-up, runs, flown
    /// gaps and run-out, on the motion model; returns its time.
    /// </summary>
    [MethodImpl(HotPath.Optimized)]
    public double Stroke(StrokeStep step)
    {
        ArgumentNullException.ThrowIfNull(step);
        var timeline = Timeline();
        var before = ElapsedSeconds;
        foreach (ref readonly var move in step.Moves)
        {
            var burn = move.Kind == MoveKind.Burn;
            if (burn != LaserOn)
            {
                LaserOn = burn;
                LaserSwitches++;
            }
        }

        var speed = timeline.XSpeedData;
        timeline.Stroke(step.Plan, step.FirstEdgeSeconds, step.LastOffSeconds);
        SpeedChanges += speed != timeline.XSpeedData ? 1 : 0;
        ElapsedSeconds = timeline.End;
        return ElapsedSeconds - before;
    }

    /// <summary>
    /// The elapsed time after the first <paramref name="moveCount"/> moves of a stroke not yet ended, as a run that has done
    /// them counts it: the stroke from a margin after the motion before, at the burn speed (its ramps and flown gaps are
    /// settled when it ends). Adds nothing.
    /// </summary>
    public double Provisional(StrokeStep step, int moveCount)
    {
        ArgumentNullException.ThrowIfNull(step);
        var timing = _timing ?? throw new InvalidOperationException("only a timed program has strokes");
        var length = 0L;
        foreach (ref readonly var move in step.Moves[..moveCount])
        {
            length += move.LengthX;
        }

        return Timeline().End + timing.MarginSeconds + (length / timing.BurnSpeed);
    }

    /// <summary>An estimator that goes on from where this one is, independently (a resume's estimate from a row's start).</summary>
    public PlanEstimator Clone()
    {
        // Member by member, so that a field added later is copied too; the timeline is the one part that is mutable.
        var copy = (PlanEstimator)MemberwiseClone();
        copy._timeline = _timeline?.Clone();
        return copy;
    }

    /// <summary>Ends the run: switches the laser off if it is on; returns the time that took.</summary>
    public double Finish()
    {
        if (_timing is not null)
        {
            // A stroke ends with its run's switch-off, taken into its time.
            LaserSwitches += LaserOn ? 1 : 0;
            LaserOn = false;
            return 0;
        }

        if (!LaserOn)
        {
            return 0;
        }

        LaserOn = false;
        LaserSwitches++;
        ElapsedSeconds += _laserOffSeconds;
        return _laserOffSeconds;
    }

    private MotionTimeline Timeline()
    {
        var timing = _timing ?? throw new InvalidOperationException("a step-by-step plan has no strokes or travels: its program is plain moves");
        return _timeline ??= new MotionTimeline(timing, StartSeconds, timing.TravelSpeedData);
    }

    private static RasterProgram Checked(RasterProgram program)
    {
        ArgumentNullException.ThrowIfNull(program);
        return program;
    }

    private double SetSpeed(ref int axisSpeedData, int wanted)
    {
        if (axisSpeedData == wanted)
        {
            return 0;
        }

        axisSpeedData = wanted;
        SpeedChanges++;
        return _roundTripSeconds;
    }

    private double AxisSeconds(long distanceMicrosteps, int speedData) =>
        _roundTripSeconds + new TrapezoidProfile(distanceMicrosteps, StageUnits.SpeedMicrostepsPerS(speedData), _accelerationMicrostepsPerS2).Duration;

    private static string Line(LaserGateProfile gate, string format, int value) =>
        string.Format(CultureInfo.InvariantCulture, format, value) + gate.LineTerminator;
}
