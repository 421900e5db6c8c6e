using System.Globalization;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Planning;

/// <summary>The process parameters of a run: speeds, acceleration, laser frequency and the two serial lines' baud rates.</summary>
public sealed record ProcessSettings
{
    /// <summary>The built-in profile's defaults.</summary>
    public static ProcessSettings Default { get; } = FromProfile(MachineProfile.Default);

    /// <summary>Stage speed while burning (and overscanning), mm/s.</summary>
    public double BurnSpeedMmPerS { get; init; } = 1;

    /// <summary>Stage speed while travelling with the laser off, mm/s (<see cref="PlanStrategy.Optimized"/> only).</summary>
    public double TravelSpeedMmPerS { get; init; } = 4;

    /// <summary>Acceleration of both axes, set once at the start of a run, mm/s².</summary>
    public double AccelerationMmPerS2 { get; init; } = 50;

    /// <summary>Q-switch frequency while burning, Hz (sent to the gate in whole Hz).</summary>
    public double LaserFrequencyHz { get; init; } = 1000;

    /// <summary>Energy of one laser pulse, µJ, when known (for the energy per pixel; nothing else uses it).</summary>
    public double? PulseEnergyUj { get; init; }

    /// <summary>Raster (burn while moving) or dots (stop and fire a burst at each dot).</summary>
    public PlanMode Mode { get; init; } = PlanMode.Raster;

    /// <summary>Pulses fired at each dot in <see cref="PlanMode.Dots"/> (1 in raster mode).</summary>
    public int PulsesPerDot { get; init; } = 1;

    /// <summary>Time the stage is given to settle at a dot before the burst, ms (<see cref="PlanMode.Dots"/> only).</summary>
    public double DotSettleMs { get; init; }

    /// <summary>
    /// Distance between dots along a run in <see cref="PlanMode.Dots"/>, whole microsteps; 0 (the default): one dot at
    /// the centre of every pixel.
    /// </summary>
    public long DotPitchMicrosteps { get; init; }

    /// <summary>Baud rate of the Zaber chain.</summary>
    public int StageBaudRate { get; init; } = 9600;

    /// <summary>Baud rate of the laser gate's line.</summary>
    public int GateBaudRate { get; init; } = 9600;

    /// <summary>The machine profile's default process values.</summary>
    public static ProcessSettings FromProfile(MachineProfile profile)
    {
        ArgumentNullException.ThrowIfNull(profile);
        return new ProcessSettings
        {
            BurnSpeedMmPerS = profile.BurnSpeedMmPerS,
            TravelSpeedMmPerS = profile.TravelSpeedMmPerS,
            AccelerationMmPerS2 = profile.AccelerationMmPerS2,
            LaserFrequencyHz = profile.LaserFrequencyHz,
            StageBaudRate = profile.StageBaudRate,
            GateBaudRate = profile.Gate.BaudRate,
        };
    }

    /// <summary>The stage speed a move of <paramref name="kind"/> runs at: the burn speed for burns and overscans, and for everything under <see cref="PlanStrategy.Paper"/>; the travel speed otherwise.</summary>
    public double SpeedMmPerS(MoveKind kind, PlanStrategy strategy) =>
        strategy == PlanStrategy.Paper || kind != MoveKind.Travel ? BurnSpeedMmPerS : TravelSpeedMmPerS;

    /// <summary>The laser frequency as the gate is sent it: whole Hz.</summary>
    public int LaserFrequencyWholeHz => (int)Math.Round(LaserFrequencyHz, MidpointRounding.AwayFromZero);

    private static string N(double value) => value.ToString(CultureInfo.InvariantCulture);
}
