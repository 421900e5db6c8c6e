using LaserEngrave.Core.Alignment;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Camera;

/// <summary>Click-to-go and marks picked in the image: camera pixels turned into stage positions through the calibration in force.</summary>
public sealed class CameraNavigator
{
    private readonly ICameraRig _rig;

    public CameraNavigator(ICameraRig rig, CameraCalibration calibration)
    {
        ArgumentNullException.ThrowIfNull(rig);
        ArgumentNullException.ThrowIfNull(calibration);
        _rig = rig;
        Calibration = calibration;
    }

    public CameraCalibration Calibration { get; }

    /// <summary>Where the stage must go, µm, to bring pixel (<paramref name="xPx"/>, <paramref name="yPx"/>) of an image taken where the stage stands now under the spot.</summary>
    public (double XUm, double YUm) TargetOf(double xPx, double yPx)
    {
        var (x, y) = _rig.Position;
        return Calibration.StageTargetUm(x, y, xPx, yPx);
    }

    /// <summary>Click to go: moves the stage (laser off) so that the clicked point comes under the spot; returns where it went, µm.</summary>
    public async Task<(double XUm, double YUm)> GoToPixelAsync(double xPx, double yPx, CancellationToken cancellationToken)
    {
        var (x, y) = TargetOf(xPx, yPx);
        await _rig.MoveToAsync(x, y, cancellationToken);
        return _rig.Position;
    }

    /// <summary>A mark picked in <paramref name="frame"/> (taken where the stage stands now): the click snapped to the mark's centre, as a stage position, µm.</summary>
    /// <param name="markDiameterUm">About how wide the mark is, µm (the snap looks within it).</param>
    public (double XUm, double YUm, double XPx, double YPx) PickMark(CameraFrame frame, double clickXPx, double clickYPx, double markDiameterUm)
    {
        ArgumentNullException.ThrowIfNull(frame);
        var diameterPx = markDiameterUm / Calibration.UmPerPixel;
        var (xPx, yPx) = MarkFinder.Locate(frame, clickXPx, clickYPx, Math.Max(8, diameterPx * 1.5), diameterPx);
        var (x, y) = TargetOf(xPx, yPx);
        return (x, y, xPx, yPx);
    }

    /// <summary>A mark picked in the image as a fiducial of the existing two-mark alignment (docs/alignment.md).</summary>
    public Fiducial PickFiducial(CameraFrame frame, double clickXPx, double clickYPx, double markDiameterUm, double jobXMm, double jobYMm)
    {
        var (x, y, _, _) = PickMark(frame, clickXPx, clickYPx, markDiameterUm);
        return new Fiducial(jobXMm, jobYMm, Units.UmToMm(x), Units.UmToMm(y));
    }
}
