using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Planning;

/// <summary>A part's speeds and acceleration as the Zaber devices take them, converted once from the process (<see cref="StageUnits"/>).</summary>
/// <param name="BurnSpeedData">Target speed data of burn runs and their run-ups and run-outs.</param>
/// <param name="TravelSpeedData">Target speed data of travels (the burn speed's under <see cref="PlanStrategy.Paper"/>).</param>
/// <param name="AccelerationData">Acceleration data of both axes.</param>
public readonly record struct MotionData(int BurnSpeedData, int TravelSpeedData, int AccelerationData)
{
    /// <summary>The motion data of <paramref name="process"/> under <paramref name="strategy"/> on a stage of <paramref name="microstepUm"/>.</summary>
    public static MotionData Of(ProcessSettings process, PlanStrategy strategy, double microstepUm)
    {
        ArgumentNullException.ThrowIfNull(process);
        return new MotionData(
            StageUnits.SpeedData(process.SpeedMmPerS(MoveKind.Burn, strategy), microstepUm),
            StageUnits.SpeedData(process.SpeedMmPerS(MoveKind.Travel, strategy), microstepUm),
            StageUnits.AccelerationData(process.AccelerationMmPerS2, microstepUm));
    }

    /// <summary>The speed data a move of <paramref name="kind"/> runs at.</summary>
    public int SpeedDataFor(MoveKind kind) => kind == MoveKind.Travel ? TravelSpeedData : BurnSpeedData;
}
