namespace LaserEngrave.Core.Camera;

/// <summary>Snaps a click near a dark mark to the mark's centre, so a pick is as good as the image, not as the hand.</summary>
/// <remarks>
/// Around the click (within <c>searchPx</c>) the darkest spot after a 3 x 3 mean is the mark; its darkness is measured
/// against the window's median brightness. The centre is the centroid of the darkness above three quarters of the
/// mark's, within the mark's diameter of its darkest spot: a flat black mark weighs evenly, and the grain's darker
/// patches stay under the threshold.
/// </remarks>
public static class MarkFinder
{
    /// <summary>Least darkness against the surroundings, grey levels, for a mark to count as found.</summary>
    public const double MinDarknessGrey = 25;

    /// <exception cref="CameraException">No mark darker than its surroundings near the click.</exception>
    public static (double XPx, double YPx) Locate(CameraFrame frame, double clickXPx, double clickYPx, double searchPx, double markDiameterPx)
    {
        ArgumentNullException.ThrowIfNull(frame);
        var image = GreyImage.Of(frame);
        var x0 = Math.Clamp((int)Math.Round(clickXPx - searchPx), 1, image.Width - 2);
        var x1 = Math.Clamp((int)Math.Round(clickXPx + searchPx), 1, image.Width - 2);
        var y0 = Math.Clamp((int)Math.Round(clickYPx - searchPx), 1, image.Height - 2);
        var y1 = Math.Clamp((int)Math.Round(clickYPx + searchPx), 1, image.Height - 2);
        var window = new List<double>();
        for (var y = y0; y <= y1; y++)
        {
            for (var x = x0; x <= x1; x++)
            {
                window.Add(image[x, y]);
            }
        }

        if (window.Count == 0)
        {
            throw new CameraException($"the click at {clickXPx:F0}, {clickYPx:F0} is outside the {image.Width} x {image.Height} image");
        }

        window.Sort();
        var background = window[window.Count / 2];
        var (bestX, bestY, best) = (0, 0, double.NegativeInfinity);
        for (var y = y0; y <= y1; y++)
        {
            for (var x = x0; x <= x1; x++)
            {
                var sum = 0.0;
                for (var j = -1; j <= 1; j++)
                {
                    for (var i = -1; i <= 1; i++)
                    {
                        sum += background - image[x + i, y + j];
                    }
                }

                if (sum / 9 > best)
                {
                    (bestX, bestY, best) = (x, y, sum / 9);
                }
            }
        }

        if (best < MinDarknessGrey)
        {
            throw new CameraException($"no mark near the click at {clickXPx:F0}, {clickYPx:F0}: nothing there is more than {MinDarknessGrey} grey levels darker than around it (darkest {Math.Max(0, best):F0}); click on the mark itself, or focus the camera");
        }

        var reach = Math.Max(2, (int)Math.Ceiling(markDiameterPx));
        var threshold = 0.75 * best;
        double sw = 0, sx = 0, sy = 0;
        for (var y = Math.Max(0, bestY - reach); y <= Math.Min(image.Height - 1, bestY + reach); y++)
        {
            for (var x = Math.Max(0, bestX - reach); x <= Math.Min(image.Width - 1, bestX + reach); x++)
            {
                var weight = background - image[x, y] - threshold;
                if (weight > 0)
                {
                    sw += weight;
                    sx += weight * x;
                    sy += weight * y;
                }
            }
        }

        return (sx / sw, sy / sw);
    }
}
