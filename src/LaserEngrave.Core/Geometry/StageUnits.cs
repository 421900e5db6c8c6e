namespace LaserEngrave.Core.Geometry;

/// <summary>The one place where millimetres, micrometres and Zaber's device units are converted.</summary>
/// <remarks>T-series firmware 5.xx: speed = data x 9.375 microsteps/s, acceleration = data x 11250 microsteps/s².</remarks>
public static class StageUnits
{
    /// <summary>Microsteps per second for one unit of Set Target Speed data.</summary>
    public const double SpeedUnitMicrostepsPerS = 9.375;

    /// <summary>Microsteps per second squared for one unit of Set Acceleration data.</summary>
    public const double AccelerationUnitMicrostepsPerS2 = 11250;

    /// <summary>Highest speed or acceleration data at 64 microsteps per step (512 x 64 - 1).</summary>
    public const int MaxSettingData = 32767;

    public static double MmToMicrosteps(double mm, double microstepUm) => Units.MmToSteps(mm, microstepUm);

    public static double MicrostepsToMm(double microsteps, double microstepUm) => Units.StepsToMm(microsteps, microstepUm);

    public static double UmToMicrosteps(double um, double microstepUm) => um / microstepUm;

    public static double MicrostepsToUm(double microsteps, double microstepUm) => microsteps * microstepUm;

    /// <summary>Set Target Speed data for a speed in mm/s, rounded to the nearest unit and kept in 1..32767.</summary>
    public static int SpeedData(double mmPerS, double microstepUm) =>
        (int)Math.Clamp(Math.Round(MmToMicrosteps(mmPerS, microstepUm) / SpeedUnitMicrostepsPerS), 1, MaxSettingData);

    /// <summary>
    /// Move At Constant Speed data for a signed speed in microsteps/s, kept in ±32767 (0: stand still); rounded half away
    /// from zero where <see cref="SpeedData"/> rounds half to even, as the vector motion has always sent it (same bytes).
    /// </summary>
    public static int SignedSpeedData(double microstepsPerS) =>
        (int)Math.Clamp(Math.Round(microstepsPerS / SpeedUnitMicrostepsPerS, MidpointRounding.AwayFromZero), -MaxSettingData, MaxSettingData);

    /// <summary>Set Acceleration data for an acceleration in mm/s², rounded to the nearest unit and kept in 1..32767.</summary>
    public static int AccelerationData(double mmPerS2, double microstepUm) =>
        (int)Math.Clamp(Math.Round(MmToMicrosteps(mmPerS2, microstepUm) / AccelerationUnitMicrostepsPerS2), 1, MaxSettingData);

    /// <summary>The speed in microsteps/s that Set Target Speed data gives.</summary>
    public static double SpeedMicrostepsPerS(int data) => data * SpeedUnitMicrostepsPerS;

    /// <summary>The acceleration in microsteps/s² that Set Acceleration data gives (0 means the maximum).</summary>
    public static double AccelerationMicrostepsPerS2(int data) => (data == 0 ? MaxSettingData : data) * AccelerationUnitMicrostepsPerS2;
}
