namespace LaserEngrave.Core.Jobs;

/// <summary>The names of a job's fields (<see cref="JobSettings"/>' properties, camelCase) as <see cref="FieldProblem"/>s name them.</summary>
/// <remarks>The app places a message beside the field of this name; the command line and the files map each to their own name.</remarks>
public static class JobField
{
    public const string Threshold = "thresholdPercent";
    public const string Width = "widthMm";
    public const string Height = "heightMm";
    public const string Pitch = "pitchUm";
    public const string OriginX = "originXMm";
    public const string OriginY = "originYMm";
    public const string Frequency = "laserFrequencyHz";
    public const string BurnSpeed = "burnSpeedMmPerS";
    public const string TravelSpeed = "travelSpeedMmPerS";
    public const string Acceleration = "accelerationMmPerS2";
    public const string Overscan = "overscanMm";
    public const string Passes = "passes";
    public const string PulseEnergy = "pulseEnergyUj";
    public const string PulsesPerDot = "pulsesPerDot";
    public const string DotPitch = "dotPitchMicrosteps";
    public const string DotSettle = "dotSettleMs";
    public const string Tolerance = "toleranceUm";
    public const string FillPitch = "fillPitchUm";

    /// <summary>A process' mode, raster or dots (a log's or a program's; the app and the command line name it by word).</summary>
    public const string Mode = "mode";

    /// <summary>The Zaber chain's baud rate as a process carries it.</summary>
    public const string StageBaud = "stageBaudRate";

    /// <summary>The laser gate's baud rate as a process carries it.</summary>
    public const string GateBaud = "gateBaudRate";

    /// <summary>What the user calls the field: "burn speed".</summary>
    public static string Label(string field) => field switch
    {
        Threshold => "threshold",
        Width => "width",
        Height => "height",
        Pitch => "pixel pitch",
        OriginX => "origin X",
        OriginY => "origin Y",
        Frequency => "laser frequency",
        BurnSpeed => "burn speed",
        TravelSpeed => "travel speed",
        Acceleration => "acceleration",
        Overscan => "overscan",
        Passes => "passes",
        PulseEnergy => "pulse energy",
        PulsesPerDot => "pulses per dot",
        DotPitch => "dot pitch",
        DotSettle => "settle time",
        Tolerance => "chord tolerance",
        FillPitch => "fill pitch",
        StageBaud => "stage baud rate",
        GateBaud => "gate baud rate",
        _ => field,
    };

    /// <summary>The field's unit with its leading space (" mm/s"), or nothing for a count.</summary>
    public static string Unit(string field) => field switch
    {
        Threshold => " %",
        Width or Height or OriginX or OriginY or Overscan => " mm",
        Pitch or Tolerance or FillPitch => " µm",
        Frequency => " Hz",
        BurnSpeed or TravelSpeed => " mm/s",
        Acceleration => " mm/s²",
        PulseEnergy => " µJ",
        DotPitch => " microsteps",
        DotSettle => " ms",
        _ => string.Empty,
    };
}
