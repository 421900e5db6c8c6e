namespace LaserEngrave.Wire.Zaber;

/// <summary>Meanings of the data of an Error (255) reply, T-series firmware 5.xx.</summary>
public static class ZaberErrorCodes
{
    public const int CannotHome = 1;
    public const int MoveAbsoluteInvalid = 20;
    public const int MoveRelativeInvalid = 21;
    public const int VelocityInvalid = 22;
    public const int ModeInvalid = 40;
    public const int SpeedInvalid = 42;
    public const int AccelerationInvalid = 43;
    public const int MaximumPositionInvalid = 44;
    public const int CurrentPositionInvalid = 45;
    public const int SettingInvalid = 53;
    public const int CommandInvalid = 64;
    public const int Busy = 255;

    public static string Describe(int code) => code switch
    {
        1 => "cannot home: home sensor not found",
        2 => "device number invalid",
        14 => "voltage low",
        15 => "voltage high",
        18 => "stored position invalid",
        20 => "absolute position out of range",
        21 => "relative move out of range",
        22 => "constant speed out of range",
        36 => "restore settings data invalid",
        37 => "microstep resolution invalid",
        38 => "running current invalid",
        39 => "hold current invalid",
        40 => "device mode invalid",
        41 => "home speed invalid",
        42 => "target speed out of range",
        43 => "acceleration out of range",
        44 => "maximum position invalid",
        45 => "current position invalid",
        46 => "maximum relative move invalid",
        47 => "home offset invalid",
        48 => "alias invalid",
        49 => "lock state invalid",
        53 => "setting number invalid",
        64 => "command invalid for this firmware",
        255 => "busy: another command is running and cannot be pre-empted",
        >= 4000 and < 4100 => $"device mode bit {code - 4000} invalid",
        _ => $"error code {code}",
    };
}
