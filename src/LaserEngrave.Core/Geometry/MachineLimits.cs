namespace LaserEngrave.Core.Geometry;

/// <summary>What a machine profile allows: the ranges every speed, acceleration, frequency and position must fall in.</summary>
/// <param name="MinSpeedMmPerS">One unit of Zaber's Set Target Speed data on the coarser axis (9.375 microsteps/s).</param>
/// <param name="MaxSpeedMmPerS">The slower axis' allowed maximum (the profile's maxSpeedMmPerS).</param>
/// <param name="MinAccelerationMmPerS2">One unit of Set Acceleration data on the coarser axis (11250 microsteps/s²).</param>
/// <param name="MaxAccelerationMmPerS2">The smaller of the axes' allowed maxima.</param>
/// <param name="MaxFrequencyHz">The highest Q-switch frequency the gate takes.</param>
/// <param name="MaxFrameFrequencyHz">The highest frequency a frame may be traced at.</param>
/// <param name="TravelXMm">X travel.</param>
/// <param name="TravelYMm">Y travel.</param>
public sealed record MachineLimits(
    double MinSpeedMmPerS,
    double MaxSpeedMmPerS,
    double MinAccelerationMmPerS2,
    double MaxAccelerationMmPerS2,
    int MaxFrequencyHz,
    int MaxFrameFrequencyHz,
    double TravelXMm,
    double TravelYMm)
{
    /// <summary>The limits of a profile that passed <see cref="MachineProfileValidator"/>.</summary>
    public static MachineLimits Of(MachineProfile profile)
    {
        ArgumentNullException.ThrowIfNull(profile);
        var coarse = Math.Max(profile.X.MicrostepUm, profile.Y.MicrostepUm);
        var limits = new MachineLimits(
            StageUnits.MicrostepsToMm(StageUnits.SpeedUnitMicrostepsPerS, coarse),
            Math.Min(profile.X.MaxSpeedMmPerS, profile.Y.MaxSpeedMmPerS),
            StageUnits.MicrostepsToMm(StageUnits.AccelerationUnitMicrostepsPerS2, coarse),
            Math.Min(profile.X.MaxAccelerationMmPerS2, profile.Y.MaxAccelerationMmPerS2),
            profile.Gate.MaxFrequencyHz,
            profile.MaxFrameFrequencyHz,
            profile.X.TravelMm,
            profile.Y.TravelMm);
        return limits with
        {
            MicrostepUm = coarse,
            TravelXMicrosteps = profile.X.TravelMicrosteps,
            TravelYMicrosteps = profile.Y.TravelMicrosteps,
        };
    }

    /// <summary>The coarser axis' microstep, µm: the smallest step the stage makes on both axes, so the smallest pixel pitch.</summary>
    public double MicrostepUm { get; init; }

    /// <summary>X travel in whole microsteps.</summary>
    public long TravelXMicrosteps { get; init; }

    /// <summary>Y travel in whole microsteps.</summary>
    public long TravelYMicrosteps { get; init; }

    /// <summary>The speed range, for messages: "0.00093..4 mm/s".</summary>
    public string SpeedRange => $"{Text.N(MinSpeedMmPerS)}..{Text.N(MaxSpeedMmPerS)} mm/s";

    /// <summary>The acceleration range, for messages: "1.116..200 mm/s²".</summary>
    public string AccelerationRange => $"{Text.N(MinAccelerationMmPerS2)}..{Text.N(MaxAccelerationMmPerS2)} mm/s²";

    public bool SpeedAllowed(double mmPerS) => double.IsFinite(mmPerS) && mmPerS >= MinSpeedMmPerS && mmPerS <= MaxSpeedMmPerS;

    public bool AccelerationAllowed(double mmPerS2) => double.IsFinite(mmPerS2) && mmPerS2 >= MinAccelerationMmPerS2 && mmPerS2 <= MaxAccelerationMmPerS2;

    /// <summary>Whether a frequency is one the gate is sent as 1..<see cref="MaxFrequencyHz"/> whole Hz.</summary>
    public bool FrequencyAllowed(double hz) => double.IsFinite(hz) && Math.Round(hz, MidpointRounding.AwayFromZero) >= 1 && hz <= MaxFrequencyHz;

    /// <summary>Whether a frequency is whole Hz, as the gate is sent it (a job refuses a fraction rather than log one value and send another).</summary>
    public static bool WholeHz(double hz) => double.IsFinite(hz) && hz == Math.Floor(hz);

    /// <summary>Numbers in messages: invariant, at most 5 decimals, and in exponent form when huge or tiny.</summary>
    internal static class Text
    {
        public static string N(double value) =>
            value != 0 && double.IsFinite(value) && (Math.Abs(value) >= 1e9 || Math.Abs(value) < 1e-5)
                ? value.ToString("G6", System.Globalization.CultureInfo.InvariantCulture)
                : value.ToString("0.#####", System.Globalization.CultureInfo.InvariantCulture);
    }
}
