using System.Text.Json.Serialization;

namespace LaserEngrave.Core.Geometry;

/// <summary>The camera on the optical path (seed 000, Fig. 2, item 4): its image size and the optics' nominal figures, and what calibration measured.</summary>
/// <remarks>
/// The nominal figures (<see cref="UmPerPixel"/>, <see cref="RotationDeg"/>, <see cref="Mirrored"/>, the spot offset) come
/// from the optics' data sheet, or are the twin's truth on the simulator; <see cref="Calibration"/> is what the app measured
/// with the camera itself (docs/camera.md) and, when present, is what click-to-go, marks and the map use.
/// </remarks>
public sealed record CameraProfile
{
    /// <summary>Image width, camera pixels.</summary>
    public int WidthPx { get; init; } = 640;

    /// <summary>Image height, camera pixels.</summary>
    public int HeightPx { get; init; } = 480;

    /// <summary>Nominal size on the sample of one camera pixel, µm (the sensor's pixel pitch over the magnification).</summary>
    public double UmPerPixel { get; init; } = 1.5;

    /// <summary>Nominal turn of the image's x axis against the stage's X axis, degrees (+X towards +Y).</summary>
    public double RotationDeg { get; init; }

    /// <summary>Whether the image is mirrored against the stage (an odd number of mirrors in the camera's path).</summary>
    public bool Mirrored { get; init; }

    /// <summary>Nominal place of the laser spot from the image's centre along the image's x axis (right), µm on the sample.</summary>
    public double SpotOffsetXUm { get; init; }

    /// <summary>Nominal place of the laser spot from the image's centre along the image's y axis (down), µm on the sample.</summary>
    public double SpotOffsetYUm { get; init; }

    /// <summary>What the app measured (`Calibrate` in the camera panel); null (absent from the file) until then.</summary>
    [JsonIgnore(Condition = JsonIgnoreCondition.WhenWritingNull)]
    public CameraCalibration? Calibration { get; init; }

    /// <summary>The figures in force: the measured ones when calibrated, else the nominal ones.</summary>
    [JsonIgnore]
    public CameraCalibration InForce => Calibration ?? Nominal;

    /// <summary>The nominal figures as a calibration (no residual: nothing was measured).</summary>
    [JsonIgnore]
    public CameraCalibration Nominal => new()
    {
        UmPerPixel = UmPerPixel,
        RotationDeg = RotationDeg,
        Mirrored = Mirrored,
        SpotXPx = ((WidthPx - 1) / 2.0) + (SpotOffsetXUm / UmPerPixel),
        SpotYPx = ((HeightPx - 1) / 2.0) + (SpotOffsetYUm / UmPerPixel),
    };
}
