namespace LaserEngrave.Core.Vectors;

/// <summary>What a stroke's command to an axis does.</summary>
public enum AxisCommandKind
{
    /// <summary>Move At Constant Speed (Zaber 22) with a signed speed: the axis ramps to it at its acceleration.</summary>
    Speed,

    /// <summary>Stop (Zaber 23): the axis brakes to rest at its acceleration.</summary>
    Stop,

    /// <summary>Return Current Position (Zaber 60): shows the stroke under way before the laser comes on.</summary>
    Query,
}
