using System.Runtime.CompilerServices;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Motion;

namespace LaserEngrave.Core.Planning;

/// <summary>The least time any executor could take for a plan's burns: motion only, no serial time, no laser switching.</summary>
/// <remarks>
/// Streams the plan's burn moves in order (docs/execution.md, "Lower bound"): every burn run at the burn speed; every gap
/// between two burn runs of one row the shortest of crossing it at the burn speed, flying it (from the burn speed up
/// towards the travel speed and back, at the acceleration) and a stop-go move (a rest-to-rest
/// <see cref="TrapezoidProfile"/> at the travel speed and the acceleration); every row change, from the last run's exit
/// edge to the next visited row's first entry edge as the plan orders them, the longer of the two axes' rest-to-rest
/// moves at the travel speed. Speeds and acceleration are the quantised Zaber ones (<see cref="StageUnits"/>), as the
/// estimator's; the travel speed is the process's whatever the strategy, since a bound asks what the machine could do.
/// </remarks>
public struct LowerBound
{
    private readonly double _burnSpeed;
    private readonly double _travelSpeed;
    private readonly double _acceleration;

    // The bound of a gap within a row depends on its length alone.
    private readonly GapMemo<double>? _gapSeconds;
    private bool _hasBurn;
    private long _lastX;
    private long _lastY;
    private int _lastRow;

    /// <summary>A bound for moves in microsteps of <paramref name="microstepUm"/> under <paramref name="process"/>.</summary>
    public LowerBound(ProcessSettings process, double microstepUm)
    {
        ArgumentNullException.ThrowIfNull(process);
        _burnSpeed = StageUnits.SpeedMicrostepsPerS(StageUnits.SpeedData(process.BurnSpeedMmPerS, microstepUm));
        _travelSpeed = StageUnits.SpeedMicrostepsPerS(StageUnits.SpeedData(process.TravelSpeedMmPerS, microstepUm));
        _acceleration = StageUnits.AccelerationMicrostepsPerS2(StageUnits.AccelerationData(process.AccelerationMmPerS2, microstepUm));
        var (burn, travel, acceleration) = (_burnSpeed, _travelSpeed, _acceleration);
        _gapSeconds = new GapMemo<double>(dx => GapSeconds(dx, burn, travel, acceleration));
    }

    /// <summary>The bound so far, s.</summary>
    public double Seconds { readonly get; private set; }

    /// <summary>The bound for every move of <paramref name="plan"/> under <paramref name="process"/>, s.</summary>
    public static double Of(RasterPlan plan, ProcessSettings process)
    {
        ArgumentNullException.ThrowIfNull(plan);
        var bound = new LowerBound(process, plan.Geometry.MicrostepUm);
        foreach (var move in plan.Moves())
        {
            bound.Add(move);
        }

        return bound.Seconds;
    }

    /// <summary>Counts one move of the plan, in order; only burns count, with what lies between them.</summary>
    [MethodImpl(HotPath.Optimized)]
    public void Add(in Move move)
    {
        if (move.Kind != MoveKind.Burn)
        {
            return;
        }

        if (_hasBurn)
        {
            long dx = Math.Abs(move.X0 - _lastX), dy = Math.Abs(move.Y0 - _lastY);
            Seconds += move.Row == _lastRow && dy == 0
                ? _gapSeconds?.Get(dx) ?? GapSeconds(dx, _burnSpeed, _travelSpeed, _acceleration)
                : Math.Max(StopGo(dx, _travelSpeed, _acceleration), StopGo(dy, _travelSpeed, _acceleration));
        }

        Seconds += move.LengthX / _burnSpeed;
        (_hasBurn, _lastX, _lastY, _lastRow) = (true, move.X1, move.Y1, move.Row);
    }

    // A gap between two runs of a row: the shortest of crossing it at the burn speed, flying it and a stop-go move.
    private static double GapSeconds(long dx, double burnSpeed, double travelSpeed, double acceleration) =>
        Math.Min(Math.Min(dx / burnSpeed, Flown(dx, burnSpeed, travelSpeed, acceleration)), StopGo(dx, travelSpeed, acceleration));

    // Speeding up from the burn speed (towards the travel speed) and back to it at the next edge, without stopping.
    private static double Flown(long distance, double burnSpeed, double travelSpeed, double acceleration)
    {
        if (travelSpeed <= burnSpeed)
        {
            return distance / burnSpeed;
        }

        var peak = Math.Min(travelSpeed, Math.Sqrt((burnSpeed * burnSpeed) + (acceleration * distance)));
        var ramps = ((peak * peak) - (burnSpeed * burnSpeed)) / acceleration;
        return (2 * (peak - burnSpeed) / acceleration) + ((distance - ramps) / peak);
    }

    private static double StopGo(long distance, double travelSpeed, double acceleration) =>
        distance == 0 ? 0 : new TrapezoidProfile(distance, travelSpeed, acceleration).Duration;
}
