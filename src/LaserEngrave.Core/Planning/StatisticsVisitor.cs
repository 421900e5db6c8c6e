using System.Runtime.CompilerServices;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Planning;

/// <summary>Adds up a plan's statistics over its program's steps (each step's moves, and the step's time) without allocating.</summary>
internal struct StatisticsVisitor : IRasterStepVisitor
{
    private readonly PlanEstimator _estimator;
    private LowerBound _lowerBound;
    private long _moves;
    private long _burnRuns;
    private long _burnMicrosteps;
    private long _overscanMicrosteps;
    private double _travelMicrosteps;

    /// <summary>Where the plan starts: the first move's start.</summary>
    public (long X, long Y)? Start { get; private set; }

    /// <summary>Where the plan ends: the last move's end.</summary>
    public (long X, long Y) End { get; private set; }

    public StatisticsVisitor(PlanEstimator estimator, LowerBound lowerBound)
    {
        _estimator = estimator;
        _lowerBound = lowerBound;
    }

    public void Travel(in TravelStep travel)
    {
        Count(travel.Move);
        _estimator.Travel(travel);
    }

    [MethodImpl(HotPath.Optimized)]
    public void Stroke(StrokeStep stroke)
    {
        foreach (ref readonly var move in stroke.Moves)
        {
            Count(move);
        }

        _estimator.Stroke(stroke);
    }

    public void Move(in MoveStep move)
    {
        Count(move.Move);
        _estimator.Move(move);
    }

    [MethodImpl(HotPath.Optimized)]
    private void Count(in Move move)
    {
        _moves++;
        Start ??= (move.X0, move.Y0);
        End = (move.X1, move.Y1);
        switch (move.Kind)
        {
            case MoveKind.Burn:
                _burnRuns++;
                _burnMicrosteps += move.LengthX;
                break;
            case MoveKind.Overscan:
                _overscanMicrosteps += move.LengthX;
                break;
            default:
                _travelMicrosteps += move.LengthY == 0 ? move.LengthX
                    : move.LengthX == 0 ? move.LengthY
                    : Math.Sqrt(((double)move.LengthX * move.LengthX) + ((double)move.LengthY * move.LengthY));
                break;
        }

        _lowerBound.Add(move);
    }

    public readonly PlanStatistics Finish(int rows, double microstepUm)
    {
        _estimator.Finish();
        return new PlanStatistics
        {
            Rows = rows,
            Moves = _moves,
            BurnRuns = _burnRuns,
            BurnLengthMm = StageUnits.MicrostepsToMm(_burnMicrosteps, microstepUm),
            TravelLengthMm = StageUnits.MicrostepsToMm(_travelMicrosteps + _overscanMicrosteps, microstepUm),
            OverscanLengthMm = StageUnits.MicrostepsToMm(_overscanMicrosteps, microstepUm),
            LaserSwitches = _estimator.LaserSwitches,
            SpeedChanges = _estimator.SpeedChanges,
            EngravingSeconds = _estimator.ElapsedSeconds,
            LowerBoundSeconds = _lowerBound.Seconds,
        };
    }
}
