using LaserEngrave.Core.Camera;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.App.Services;

/// <summary>What the camera panel needs of the machine: the camera's figures, the twin's frames, the stage's place, moves with the laser off, calibration.</summary>
public interface ICameraService
{
    /// <summary>Raised when the connection, the profile, the stage's position or the job changed (from any thread).</summary>
    event EventHandler? Changed;

    /// <summary>The camera's figures: the profile's camera section, or on the simulator the twin's default camera; null without either.</summary>
    CameraProfile? Camera { get; }

    /// <summary>Whether frames come from the twin (the app is connected to the simulator) rather than a camera in the page.</summary>
    bool IsTwin { get; }

    /// <summary>Where the stage stands, µm; null before it is known.</summary>
    (double XUm, double YUm)? StagePositionUm { get; }

    /// <summary>The job's rectangle on the stage, µm (left, top, right, bottom); null without a planned job.</summary>
    (double Left, double Top, double Right, double Bottom)? JobBoxUm { get; }

    /// <summary>Whether the stage can move now (connected, nothing else holding the machine).</summary>
    bool CanMove { get; }

    /// <summary>The twin camera's frame at the stage's position now; null unless <see cref="IsTwin"/>.</summary>
    CameraFrame? TwinFrame();

    /// <summary>Laser off, then the stage to (<paramref name="xUm"/>, <paramref name="yUm"/>), through the test moves; throws <see cref="CameraException"/> with their error.</summary>
    Task GoToAsync(double xUm, double yUm, CancellationToken cancellationToken);

    /// <summary>Measures the camera with known jogs and one test dot (<see cref="CameraCalibrator"/>) and keeps the result in the profile in use.</summary>
    Task<CameraCalibrationResult> CalibrateAsync(CancellationToken cancellationToken);

    /// <summary>
    /// Scans the rectangle of stage positions from (<paramref name="x0Um"/>, <paramref name="y0Um"/>), <paramref name="widthUm"/> x
    /// <paramref name="heightUm"/> µm, frame by frame (laser off) and stitches it (<see cref="MapStitcher"/>); the stage goes back
    /// to where it stood. Throws <see cref="CameraException"/> with the reason it could not.
    /// </summary>
    Task<SampleMap> ScanMapAsync(double x0Um, double y0Um, double widthUm, double heightUm, CancellationToken cancellationToken);
}
