namespace LaserEngrave.Core.Camera;

/// <summary>The sharpness figure: how strongly brightness changes from pixel to pixel, for the live focus readout and the focus sweep.</summary>
/// <remarks>
/// The mean squared gradient (neighbour differences along x and y) over the mean brightness squared, times 1000: a blur
/// lowers it, and a brighter light alone does not raise it. Camera noise adds a floor, the same at every Z, so the sweep's
/// peak stays where the image is sharpest.
/// </remarks>
public static class FocusMeasure
{
    public static double Sharpness(CameraFrame frame)
    {
        ArgumentNullException.ThrowIfNull(frame);
        return Sharpness(GreyImage.Of(frame));
    }

    public static double Sharpness(GreyImage image)
    {
        ArgumentNullException.ThrowIfNull(image);
        double sum = 0, energy = 0;
        var count = 0;
        for (var y = 0; y < image.Height - 1; y++)
        {
            for (var x = 0; x < image.Width - 1; x++)
            {
                var here = image[x, y];
                var gx = image[x + 1, y] - here;
                var gy = image[x, y + 1] - here;
                energy += (gx * gx) + (gy * gy);
                sum += here;
                count++;
            }
        }

        if (count == 0 || sum <= 0)
        {
            return 0;
        }

        var mean = sum / count;
        return 1000 * energy / count / (mean * mean);
    }
}
