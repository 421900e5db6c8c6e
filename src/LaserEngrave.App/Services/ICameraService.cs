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

    /// <summary>Raised when a measurement wants a live frame: the page answers with <see cref="SubmitLiveFrame"/> (from any thread).</summary>
    event EventHandler? LiveFrameWanted;

    /// <summary>The page's live camera is playing, so frames can be asked for.</summary>
    bool LiveCameraReady { get; set; }

    /// <summary>The size the page sends live frames at: the profile's image, shrunk by a whole factor to at most 640 x 480.</summary>
    (int Width, int Height) LiveFrameSize { get; }

    /// <summary>A grey live frame from the page, row by row; null when taken, otherwise why it was refused (wrong size or length, too soon after the last).</summary>
    string? SubmitLiveFrame(int width, int height, byte[] grey);

    /// <summary>The next frame to measure: the twin's now, or the first the page sends after this call.</summary>
    Task<CameraFrame> CaptureAsync(CancellationToken cancellationToken);

    /// <summary>The machine's focus (Z) axis; null without one.</summary>
    ZAxisProfile? FocusAxis { get; }

    /// <summary>
    /// Steps Z from <paramref name="fromUm"/> to <paramref name="toUm"/> (µm from the visible focus) by <paramref name="stepUm"/>, laser off,
    /// measuring the sharpness at each step (<see cref="FocusSweep"/>); Z goes back where it stood when that is known.
    /// </summary>
    Task<FocusSweepResult> FindFocusAsync(double fromUm, double toUm, double stepUm, IProgress<FocusPoint>? progress, CancellationToken cancellationToken);

    /// <summary>Laser off, then Z to <paramref name="offsetUm"/> µm from the visible focus; throws <see cref="CameraException"/> with why not.</summary>
    Task MoveFocusAsync(double offsetUm, CancellationToken cancellationToken);

    /// <summary>
    /// A mark clicked at (<paramref name="xPx"/>, <paramref name="yPx"/>) in a frame taken where the stage stands: snapped to
    /// the dark mark's centre (<see cref="MarkFinder"/>) and turned into the stage position that brings it under the spot, µm.
    /// </summary>
    Task<(double XUm, double YUm, double XPx, double YPx)> PickMarkAsync(double xPx, double yPx, double markDiameterUm, CancellationToken cancellationToken);
}
