using System.Globalization;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Motion;

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
    private const int ZaberFrameBytes = 6;
    private const double BitsPerByte = 10;

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

    // Timed switching: the stroke being added (length so far, time provisionally counted) and the last motion's peak speed.
    private MotionTimeline? _timeline;
    private bool _inStroke;
    private long _strokeLength;
    private long _strokeRunUp;
    private long _strokeLastOff;
    private double _strokeStartGuess;
    private readonly List<(long Exit, long Entry)> _strokeGaps = [];
    private long _strokeGapStart = -1;

    // Every stroke is planned into this one, so a plan of millions of strokes allocates nothing per stroke.
    private readonly StrokePlan _stroke = new();

    /// <param name="process">Speeds, acceleration, frequency and baud rates.</param>
    /// <param name="strategy">The plan's strategy.</param>
    /// <param name="microstepUm">The stage's microstep.</param>
    /// <param name="gate">The gate's command strings (default: <see cref="LaserGateProfile"/>'s defaults).</param>
    /// <param name="timing">For an optimized plan made with timed switching: the model the executor runs it by (docs/execution.md).</param>
    public PlanEstimator(ProcessSettings process, PlanStrategy strategy, double microstepUm, LaserGateProfile? gate = null, TimedSwitching? timing = null)
    {
        ArgumentNullException.ThrowIfNull(process);
        process.Validate();
        gate ??= new LaserGateProfile();
        _strategy = strategy;

        _roundTripSeconds = 2 * ZaberFrameBytes * BitsPerByte / process.StageBaudRate;
        var gateByteSeconds = BitsPerByte / process.GateBaudRate;
        var onCommand = Line(gate, gate.FrequencyCommand, process.LaserFrequencyWholeHz);
        var onReply = gate.AckPrefix + " " + Line(gate, gate.FrequencyCommand, process.LaserFrequencyWholeHz);
        var offCommand = gate.OffCommand + gate.LineTerminator;
        var offReply = gate.AckPrefix + " " + Line(gate, gate.FrequencyCommand, 0);
        _laserOnSeconds = (onCommand.Length + onReply.Length) * gateByteSeconds;
        _laserOffSeconds = (offCommand.Length + offReply.Length) * gateByteSeconds;

        _accelerationMicrostepsPerS2 = StageUnits.AccelerationMicrostepsPerS2(StageUnits.AccelerationData(process.AccelerationMmPerS2, microstepUm));
        _burnSpeedData = StageUnits.SpeedData(process.SpeedMmPerS(MoveKind.Burn, strategy), microstepUm);
        _travelSpeedData = StageUnits.SpeedData(process.SpeedMmPerS(MoveKind.Travel, strategy), microstepUm);

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

    /// <summary>Advances over one move; returns its time (laser command, speed changes and motion).</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public double Add(in Move move)
    {
        if (_timing is not null)
        {
            return AddTimed(move, _timing);
        }

        var seconds = 0.0;
        if (move.Kind == MoveKind.Burn)
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

        var speedData = _strategy == PlanStrategy.Optimized && move.Kind == MoveKind.Travel ? _travelSpeedData : _burnSpeedData;
        var dx = move.LengthX;
        var dy = move.LengthY;
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

    /// <summary>Ends the run: switches the laser off if it is on; returns the time that took.</summary>
    public double Finish()
    {
        if (_timing is not null)
        {
            LaserSwitches += LaserOn ? 1 : 0;
            LaserOn = false;
            return _timeline is null ? 0 : EndStroke(_timing, _timeline);
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

    // A stroke is one move from rest to rest at the burn speed over its run-up, runs, crossed gaps and run-out; a travel
    // is a stop-go move of one or both axes; MotionTimeline says when each starts and ends.
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    private double AddTimed(in Move move, TimedSwitching timing)
    {
        var before = ElapsedSeconds;
        var timeline = _timeline ??= new MotionTimeline(timing, StartSeconds, timing.TravelSpeedData);
        var burn = move.Kind == MoveKind.Burn;
        if (burn != LaserOn)
        {
            LaserOn = burn;
            LaserSwitches++;
        }

        if (move.Kind == MoveKind.Travel)
        {
            EndStroke(timing, timeline);
            var speed = timeline.XSpeedData;
            timeline.Travel(move.LengthX, move.LengthY);
            SpeedChanges += speed != timeline.XSpeedData ? 1 : 0;
            ElapsedSeconds = timeline.End;
        }
        else
        {
            if (!_inStroke)
            {
                _inStroke = true;
                _strokeLength = 0;
                _strokeRunUp = move.Kind == MoveKind.Overscan ? move.LengthX : 0;
                _strokeLastOff = 0;
                _strokeStartGuess = timeline.End + timing.MarginSeconds;
                _strokeGaps.Clear();
                _strokeGapStart = -1;
            }

            // Provisionally at the burn speed; the ramps, the flown gaps and the start are settled when the stroke ends.
            if (burn && _strokeGapStart >= 0)
            {
                _strokeGaps.Add((_strokeGapStart, _strokeLength));
            }

            _strokeGapStart = !burn && _strokeLastOff == _strokeLength && _strokeLength > 0 ? _strokeLength : -1;
            _strokeLength += move.LengthX;
            if (burn)
            {
                _strokeLastOff = _strokeLength;
            }

            ElapsedSeconds = _strokeStartGuess + (_strokeLength / timing.BurnSpeed);
        }

        return ElapsedSeconds - before;
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    private double EndStroke(TimedSwitching timing, MotionTimeline timeline)
    {
        if (!_inStroke)
        {
            return 0;
        }

        _inStroke = false;
        var before = ElapsedSeconds;
        var speed = timeline.XSpeedData;
        var stroke = _stroke;
        stroke.Replan(timing, _strokeLength, CollectionsMarshal.AsSpan(_strokeGaps));
        timeline.Stroke(stroke, stroke.TimeAt(_strokeRunUp), stroke.TimeAt(_strokeLastOff));
        SpeedChanges += speed != timeline.XSpeedData ? 1 : 0;
        ElapsedSeconds = timeline.End;
        return ElapsedSeconds - before;
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
