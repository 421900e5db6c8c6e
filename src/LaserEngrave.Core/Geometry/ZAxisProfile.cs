using System.Text.Json.Serialization;

namespace LaserEngrave.Core.Geometry;

/// <summary>The focus (Z) axis: a third Zaber device on the stage's chain, with the visible focus and the range Z may move in.</summary>
/// <remarks>
/// Positions are absolute, from the device's home (0). A focus position of the job is an offset in µm from
/// <see cref="FocusMm"/>; it reaches the device as whole microsteps through <see cref="MicrostepsAt"/>, rounded once.
/// </remarks>
public sealed record ZAxisProfile : AxisProfile
{
    public ZAxisProfile()
    {
        DeviceNumber = 3;
        TravelMm = 25;
        MaxSpeedMmPerS = 2;
    }

    /// <summary>Where the beam is in focus by eye (the visible-light focus), mm from home: the focal series' 0.</summary>
    public double FocusMm { get; init; } = 12.5;

    /// <summary>The speed of every Z move, mm/s (at most <see cref="AxisProfile.MaxSpeedMmPerS"/>).</summary>
    public double SpeedMmPerS { get; init; } = 1;

    /// <summary>The lowest position Z may be sent to, mm from home (a lens that would touch the sample below it).</summary>
    public double MinMm { get; init; }

    /// <summary>The highest position Z may be sent to, mm from home; null: the end of the travel.</summary>
    [JsonIgnore(Condition = JsonIgnoreCondition.WhenWritingNull)]
    public double? MaxMm { get; init; }

    /// <summary>The upper limit in force: <see cref="MaxMm"/> or the travel.</summary>
    [JsonIgnore]
    public double UpperMm => MaxMm ?? TravelMm;

    /// <summary>Set Target Speed data of every Z move (<see cref="SpeedMmPerS"/>).</summary>
    [JsonIgnore]
    public int SpeedData => StageUnits.SpeedData(SpeedMmPerS, MicrostepUm);

    /// <summary>Set Acceleration data of Z for the profile's <paramref name="accelerationMmPerS2"/>, at most <see cref="AxisProfile.MaxAccelerationMmPerS2"/>.</summary>
    public int AccelerationData(double accelerationMmPerS2) => StageUnits.AccelerationData(Math.Min(accelerationMmPerS2, MaxAccelerationMmPerS2), MicrostepUm);

    /// <summary>The absolute Z position, whole microsteps, of the focus <paramref name="offsetUm"/> µm from <see cref="FocusMm"/> (rounded once, from absolute µm).</summary>
    public long MicrostepsAt(double offsetUm) =>
        (long)Math.Round(StageUnits.UmToMicrosteps(Units.MmToUm(FocusMm) + offsetUm, MicrostepUm));

    /// <summary>Null when the focus <paramref name="offsetUm"/> µm from <see cref="FocusMm"/> lies in <see cref="MinMm"/>..<see cref="UpperMm"/>; otherwise why not.</summary>
    public string? OffsetProblem(double offsetUm)
    {
        var atMm = FocusMm + Units.UmToMm(offsetUm);
        return double.IsFinite(offsetUm) && atMm >= MinMm && atMm <= UpperMm
            ? null
            : $"puts Z at {MachineLimits.Text.N(atMm)} mm, outside z.minMm..z.maxMm {MachineLimits.Text.N(MinMm)}..{MachineLimits.Text.N(UpperMm)} mm (the visible focus z.focusMm is {MachineLimits.Text.N(FocusMm)} mm)";
    }
}
