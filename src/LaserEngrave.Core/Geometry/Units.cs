namespace LaserEngrave.Core.Geometry;

/// <summary>
/// The one place for the factor of a thousand between the units a job is given in: mm and µm, seconds and ms, and a
/// count of steps of a pitch in µm (pixels, modules, microsteps) against mm. <see cref="StageUnits"/> adds Zaber's units.
/// </summary>
/// <remarks>
/// Each is the plain product or quotient by a thousand, in that order (never a product with a thousandth), so that a figure
/// converted here is the same to the last bit as the expression it replaced.
/// </remarks>
public static class Units
{
    private const double PerThousand = 1000.0;

    public static double MmToUm(double mm) => mm * PerThousand;

    public static double UmToMm(double um) => um / PerThousand;

    /// <summary>Metres from millimetres (a speed in mm/s as m/s).</summary>
    public static double MmToM(double mm) => mm / PerThousand;

    public static double MsToSeconds(double ms) => ms / PerThousand;

    public static double SecondsToMs(double seconds) => seconds * PerThousand;

    /// <summary>The length of <paramref name="steps"/> steps of <paramref name="stepUm"/> µm each (pixels, modules, microsteps), mm.</summary>
    public static double StepsToMm(double steps, double stepUm) => steps * stepUm / PerThousand;

    /// <summary>How many steps of <paramref name="stepUm"/> µm make <paramref name="mm"/> (not rounded).</summary>
    public static double MmToSteps(double mm, double stepUm) => mm * PerThousand / stepUm;
}
