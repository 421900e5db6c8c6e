namespace LaserEngrave.Wire.Zaber;

/// <summary>Zaber binary protocol command numbers used by LaserEngrave (T-series firmware 5.xx).</summary>
public enum ZaberCommand : byte
{
    Reset = 0,
    Home = 1,
    Renumber = 2,
    MoveTracking = 8,
    LimitActive = 9,
    ManualMoveTracking = 10,
    MoveAbsolute = 20,
    MoveRelative = 21,
    MoveAtConstantSpeed = 22,
    Stop = 23,
    SetDeviceMode = 40,
    SetHomeSpeed = 41,
    SetTargetSpeed = 42,
    SetAcceleration = 43,
    SetMaximumPosition = 44,
    SetCurrentPosition = 45,
    ReturnDeviceId = 50,
    ReturnFirmwareVersion = 51,
    ReturnSetting = 53,
    ReturnStatus = 54,
    EchoData = 55,
    ReturnCurrentPosition = 60,
    Error = 255,
}
