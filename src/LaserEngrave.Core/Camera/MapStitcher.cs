using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Camera;

/// <summary>Scans a region of the sample frame by frame (laser off) and stitches the frames into one map in stage axes.</summary>
/// <remarks>
/// Frames are taken on a grid whose step is four fifths of the largest stage-aligned rectangle inside one image, so
/// neighbours overlap by a fifth or more. Each map pixel takes the bilinear sample of the frame whose centre is nearest,
/// placed by the stage's position and the calibration alone: that is how a job placed on the map will land. The seams
/// are then measured, not assumed: for each pair of neighbours, the picture shift the calibration predicts is compared
/// with the shift phase correlation measures on their overlap (<see cref="MapSeam"/>).
/// </remarks>
public sealed class MapStitcher
{
    private readonly ICameraRig _rig;
    private readonly CameraCalibration _calibration;

    public MapStitcher(ICameraRig rig, CameraCalibration calibration)
    {
        ArgumentNullException.ThrowIfNull(rig);
        ArgumentNullException.ThrowIfNull(calibration);
        _rig = rig;
        _calibration = calibration;
    }

    /// <summary>Largest map side, pixels.</summary>
    public const int MaxMapSidePx = 8192;

    /// <summary>Scans the rectangle from (<paramref name="x0Um"/>, <paramref name="y0Um"/>), <paramref name="widthUm"/> x <paramref name="heightUm"/> µm of stage positions, and stitches it at <paramref name="mapUmPerPixel"/>.</summary>
    public async Task<SampleMap> ScanAsync(double x0Um, double y0Um, double widthUm, double heightUm, double mapUmPerPixel, CancellationToken cancellationToken, IProgress<int>? progress = null)
    {
        if (!(widthUm > 0 && heightUm > 0 && mapUmPerPixel > 0))
        {
            throw new CameraException($"a map needs a width, a height and a map scale above 0 (got {widthUm} x {heightUm} µm at {mapUmPerPixel} µm a pixel)");
        }

        var first = await _rig.CaptureAsync(cancellationToken);
        var (w, h) = (first.Width, first.Height);
        var t = _calibration.RotationDeg * Math.PI / 180;
        var (fw, fh) = (w * _calibration.UmPerPixel, h * _calibration.UmPerPixel);
        // The image's sides nearest the stage's axes, and its turn from them (0..45°): a stage-aligned rectangle of about
        // along cos - across sin by across cos - along sin lies inside it (never less than a fifth of the shorter side).
        var phi = Math.Abs(Math.IEEERemainder(t, Math.PI / 2));
        var (along, across) = Math.Abs(Math.Cos(t)) < Math.Abs(Math.Sin(t)) ? (fh, fw) : (fw, fh);
        var least = 0.2 * Math.Min(fw, fh);
        var insideX = Math.Max((along * Math.Cos(phi)) - (across * Math.Sin(phi)), least);
        var insideY = Math.Max((across * Math.Cos(phi)) - (along * Math.Sin(phi)), least);
        var columns = Math.Max(1, (int)Math.Ceiling(widthUm / (0.8 * insideX)) + 1);
        var rows = Math.Max(1, (int)Math.Ceiling(heightUm / (0.8 * insideY)) + 1);
        var (stepX, stepY) = (columns > 1 ? widthUm / (columns - 1) : 0, rows > 1 ? heightUm / (rows - 1) : 0);
        var mapW = (int)Math.Ceiling(widthUm / mapUmPerPixel) + 1;
        var mapH = (int)Math.Ceiling(heightUm / mapUmPerPixel) + 1;
        if (mapW > MaxMapSidePx || mapH > MaxMapSidePx)
        {
            throw new CameraException($"the map would be {mapW} x {mapH} pixels, more than {MaxMapSidePx} a side: choose a coarser map scale or a smaller area");
        }

        // Frame positions: the image's centre over each grid point.
        var (centreDx, centreDy) = _calibration.OffsetUm((w - 1) / 2.0, (h - 1) / 2.0);
        var frames = new List<MapFrame>();
        for (var row = 0; row < rows; row++)
        {
            for (var column = 0; column < columns; column++)
            {
                // Rows alternate in direction, so the stage never travels back across the region.
                var col = row % 2 == 0 ? column : columns - 1 - column;
                await _rig.MoveToAsync(x0Um + (col * stepX) - centreDx, y0Um + (row * stepY) - centreDy, cancellationToken);
                var (px, py) = _rig.Position;
                frames.Add(new MapFrame(px, py, await _rig.CaptureAsync(cancellationToken)));
                progress?.Report(frames.Count);
            }
        }

        var images = frames.Select(f => GreyImage.Of(f.Frame)).ToList();
        var map = Stitch(frames, images, x0Um, y0Um, mapW, mapH, mapUmPerPixel, centreDx, centreDy);
        return new SampleMap(map, x0Um, y0Um, mapUmPerPixel, frames, MeasureSeams(frames, images, stepX, stepY));
    }

    private CameraFrame Stitch(List<MapFrame> frames, List<GreyImage> images, double x0, double y0, int mapW, int mapH, double umPerPixel, double centreDx, double centreDy)
    {
        var pixels = new byte[mapW * mapH];
        for (var my = 0; my < mapH; my++)
        {
            var y = y0 + (my * umPerPixel);
            for (var mx = 0; mx < mapW; mx++)
            {
                var x = x0 + (mx * umPerPixel);
                var nearest = 0;
                var nearestDistance = double.PositiveInfinity;
                for (var k = 0; k < frames.Count; k++)
                {
                    var dx = x - (frames[k].StageXUm + centreDx);
                    var dy = y - (frames[k].StageYUm + centreDy);
                    var distance = (dx * dx) + (dy * dy);
                    if (distance < nearestDistance)
                    {
                        (nearest, nearestDistance) = (k, distance);
                    }
                }

                var (u, v) = _calibration.PixelAt(x - frames[nearest].StageXUm, y - frames[nearest].StageYUm);
                var value = images[nearest].Sample(u, v);
                pixels[(my * mapW) + mx] = double.IsNaN(value) ? (byte)0 : (byte)Math.Clamp(Math.Round(value), 0, 255);
            }
        }

        return new CameraFrame(mapW, mapH, pixels);
    }

    // Neighbours are frames whose stage positions differ by about one grid step along one axis.
    private List<MapSeam> MeasureSeams(List<MapFrame> frames, List<GreyImage> images, double stepX, double stepY)
    {
        var seams = new List<MapSeam>();
        for (var i = 0; i < frames.Count; i++)
        {
            for (var j = i + 1; j < frames.Count; j++)
            {
                var dx = frames[j].StageXUm - frames[i].StageXUm;
                var dy = frames[j].StageYUm - frames[i].StageYUm;
                var alongX = stepX > 0 && Math.Abs(Math.Abs(dx) - stepX) < 0.01 * stepX && Math.Abs(dy) < 0.01 * Math.Max(stepX, stepY);
                var alongY = stepY > 0 && Math.Abs(Math.Abs(dy) - stepY) < 0.01 * stepY && Math.Abs(dx) < 0.01 * Math.Max(stepX, stepY);
                if (alongX || alongY)
                {
                    seams.Add(MeasureSeam(i, j, images[i], images[j], dx, dy));
                }
            }
        }

        return seams;
    }

    // The overlap of frame i, cropped, against the same sample area in frame j (at the predicted whole-pixel shift); the measured rest is the seam's error.
    private MapSeam MeasureSeam(int i, int j, GreyImage a, GreyImage b, double dx, double dy)
    {
        var (px, py) = _calibration.PixelAt(dx, dy);
        var (sx, sy) = (-(px - _calibration.SpotXPx), -(py - _calibration.SpotYPx));
        var (rx, ry) = ((int)Math.Round(sx), (int)Math.Round(sy));
        const int margin = 4;
        var x0 = Math.Max(margin, margin - rx);
        var y0 = Math.Max(margin, margin - ry);
        var x1 = Math.Min(a.Width - margin, b.Width - margin - rx);
        var y1 = Math.Min(a.Height - margin, b.Height - margin - ry);
        if (x1 - x0 < 16 || y1 - y0 < 16)
        {
            throw new CameraException($"frames {i + 1} and {j + 1} of the map hardly overlap: the calibration's scale or turn is far off; calibrate the camera first");
        }

        var cropA = a.Crop(x0, y0, x1 - x0, y1 - y0);
        var cropB = b.Crop(x0 + rx, y0 + ry, x1 - x0, y1 - y0);
        var rest = ImageRegistration.Measure(cropA, cropB);
        return new MapSeam(i, j, sx, sy, rx + rest.XPx, ry + rest.YPx);
    }
}
