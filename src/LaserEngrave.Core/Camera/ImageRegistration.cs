using System.Numerics;
using MathNet.Numerics.IntegralTransforms;

namespace LaserEngrave.Core.Camera;

/// <summary>How far the picture moved between two images, pixels: content at q in the first is at q + (<paramref name="XPx"/>, <paramref name="YPx"/>) in the second.</summary>
/// <param name="Peak">Height of the phase correlation's peak, 0..1: the share of the images that moved together.</param>
/// <param name="MisfitGrey">Root-mean-square difference of the overlapping pixels after the shift, grey levels.</param>
public readonly record struct ImageShift(double XPx, double YPx, double Peak, double MisfitGrey);

/// <summary>Image registration by phase correlation (MathNet.Numerics' FFT), refined to a hundredth of a pixel by least squares.</summary>
/// <remarks>
/// Phase correlation finds the whole-pixel shift whatever the brightness or the texture's scale: both images are
/// windowed (Hann) against their borders, the normalised cross-power spectrum's inverse peaks at the shift, and a
/// parabola through the peak and its neighbours gives a first fraction. A few Gauss-Newton steps on the overlapping
/// pixels (bilinear samples of the second image) then bring the shift to where the images agree best, which the
/// parabola alone misses by up to a tenth of a pixel. Too little texture is refused before any of this
/// (<see cref="TextureProblem"/>), and a weak peak after it.
/// </remarks>
public static class ImageRegistration
{
    /// <summary>Least brightness spread (grey levels, standard deviation) an image must have to be tracked.</summary>
    public const double MinSpreadGrey = 4;

    /// <summary>Lowest correlation peak accepted as a found shift.</summary>
    public const double MinPeak = 0.03;

    /// <summary>Null when <paramref name="image"/> has texture enough to track; otherwise a sentence saying why not.</summary>
    public static string? TextureProblem(GreyImage image)
    {
        ArgumentNullException.ThrowIfNull(image);
        var spread = image.Spread();
        return spread >= MinSpreadGrey
            ? null
            : $"the image has too little texture to track: its brightness varies by only {spread:F1} grey levels (at least {MinSpreadGrey} needed); put a textured part of the sample (a scratch, paper, an earlier burn) under the objective, focus it, or light it better";
    }

    /// <summary>The shift of <paramref name="second"/> against <paramref name="first"/> (same size).</summary>
    /// <exception cref="CameraException">Too little texture, or no shift found.</exception>
    public static ImageShift Measure(GreyImage first, GreyImage second)
    {
        ArgumentNullException.ThrowIfNull(first);
        ArgumentNullException.ThrowIfNull(second);
        if (first.Width != second.Width || first.Height != second.Height)
        {
            throw new ArgumentException($"the images differ in size: {first.Width} x {first.Height} and {second.Width} x {second.Height}", nameof(second));
        }

        if ((TextureProblem(first) ?? TextureProblem(second)) is { } problem)
        {
            throw new CameraException(problem);
        }

        var (x, y, peak) = PhaseCorrelate(first, second);
        if (peak < MinPeak)
        {
            throw new CameraException($"the two images could not be matched (correlation peak {peak:F3}, at least {MinPeak} needed): the move was larger than the image shows, or the picture changed between them");
        }

        (x, y) = Refine(first, second, x, y);
        return new ImageShift(x, y, peak, Misfit(first, second, x, y));
    }

    /// <summary>Refines a shift already known to about a pixel (<paramref name="guessX"/>, <paramref name="guessY"/>) on the images' overlap; returns the refined shift.</summary>
    /// <remarks>
    /// Gauss-Newton on the sum of squared differences, in the inverse-compositional form: the gradients (central
    /// differences) and their normal matrix come from the first image once, so each step samples the second image only
    /// once per pixel. The steps converge to the same least-squares shift as gradients of the second image would, at a
    /// fifth of the work (a map's seams measure a hundred overlaps).
    /// </remarks>
    public static (double XPx, double YPx) Refine(GreyImage first, GreyImage second, double guessX, double guessY)
    {
        ArgumentNullException.ThrowIfNull(first);
        ArgumentNullException.ThrowIfNull(second);
        int w = first.Width, h = first.Height, sw = second.Width, sh = second.Height;
        var f = first.Values;
        var g = second.Values;
        var gradX = new double[w * h];
        var gradY = new double[w * h];
        for (var v = 1; v < h - 1; v++)
        {
            for (var u = 1; u < w - 1; u++)
            {
                var i = (v * w) + u;
                gradX[i] = 0.5 * (f[i + 1] - f[i - 1]);
                gradY[i] = 0.5 * (f[i + w] - f[i - w]);
            }
        }

        var (x, y) = (guessX, guessY);
        for (var iteration = 0; iteration < 12; iteration++)
        {
            double hxx = 0, hxy = 0, hyy = 0, bx = 0, by = 0;
            // Only pixels whose shifted place lies inside the second image's pixel centres take part.
            var ix = (int)Math.Floor(x);
            var iy = (int)Math.Floor(y);
            var (fx, fy) = (x - ix, y - iy);
            var u0 = Math.Max(1, -ix);
            var u1 = Math.Min(w - 2, sw - 2 - ix);
            var v0 = Math.Max(1, -iy);
            var v1 = Math.Min(h - 2, sh - 2 - iy);
            for (var v = v0; v <= v1; v++)
            {
                var k = ((v + iy) * sw) + u0 + ix;
                var i = (v * w) + u0;
                for (var u = u0; u <= u1; u++, k++, i++)
                {
                    var top = g[k] + ((g[k + 1] - g[k]) * fx);
                    var bottom = g[k + sw] + ((g[k + sw + 1] - g[k + sw]) * fx);
                    var e = top + ((bottom - top) * fy) - f[i];
                    var (gx, gy) = (gradX[i], gradY[i]);
                    hxx += gx * gx;
                    hxy += gx * gy;
                    hyy += gy * gy;
                    bx += gx * e;
                    by += gy * e;
                }
            }

            var det = (hxx * hyy) - (hxy * hxy);
            if (!(det > 0))
            {
                break;
            }

            // first(q + d) matches second(q + p) after the step, so the shift becomes p - d.
            var dx = ((hyy * bx) - (hxy * by)) / det;
            var dy = ((hxx * by) - (hxy * bx)) / det;
            x -= dx;
            y -= dy;
            if (Math.Abs(dx) < 1e-4 && Math.Abs(dy) < 1e-4)
            {
                break;
            }
        }

        return (x, y);
    }

    /// <summary>Root-mean-square difference, grey levels, of the overlapping pixels with <paramref name="second"/> shifted back by (x, y).</summary>
    public static double Misfit(GreyImage first, GreyImage second, double x, double y)
    {
        ArgumentNullException.ThrowIfNull(first);
        ArgumentNullException.ThrowIfNull(second);
        double sum = 0;
        var count = 0;
        for (var v = 0; v < first.Height; v++)
        {
            for (var u = 0; u < first.Width; u++)
            {
                var b = second.Sample(u + x, v + y);
                if (!double.IsNaN(b))
                {
                    sum += (first[u, v] - b) * (first[u, v] - b);
                    count++;
                }
            }
        }

        return count == 0 ? double.NaN : Math.Sqrt(sum / count);
    }

    // Whole-pixel shift and the parabola's fraction, from the inverse of the normalised cross-power spectrum.
    private static (double X, double Y, double Peak) PhaseCorrelate(GreyImage first, GreyImage second)
    {
        // Zero-padded to powers of two: MathNet's radix-2 transform, several times faster than its any-length (Bluestein) one.
        var w = (int)System.Numerics.BitOperations.RoundUpToPowerOf2((uint)first.Width);
        var h = (int)System.Numerics.BitOperations.RoundUpToPowerOf2((uint)first.Height);
        var a = Windowed(first, w, h);
        var b = Windowed(second, w, h);
        Transform2D(a, w, h, inverse: false);
        Transform2D(b, w, h, inverse: false);
        for (var i = 0; i < a.Length; i++)
        {
            var cross = b[i] * Complex.Conjugate(a[i]);
            var magnitude = cross.Magnitude;
            a[i] = magnitude > 1e-12 ? cross / magnitude : Complex.Zero;
        }

        Transform2D(a, w, h, inverse: true);
        var best = 0;
        for (var i = 1; i < a.Length; i++)
        {
            if (a[i].Real > a[best].Real)
            {
                best = i;
            }
        }

        int px = best % w, py = best / w;
        double At(int x, int y) => a[(((y % h) + h) % h * w) + (((x % w) + w) % w)].Real;
        var peak = At(px, py);
        var fx = Vertex(At(px - 1, py), peak, At(px + 1, py));
        var fy = Vertex(At(px, py - 1), peak, At(px, py + 1));
        var sx = px > w / 2 ? px - w : px;
        var sy = py > h / 2 ? py - h : py;
        return (sx + fx, sy + fy, peak);
    }

    // Rows, then columns, with MathNet's 1-D FFT (any length): its managed provider has no multi-dimensional transform.
    private static void Transform2D(Complex[] values, int w, int h, bool inverse)
    {
        var row = new Complex[w];
        for (var y = 0; y < h; y++)
        {
            Array.Copy(values, y * w, row, 0, w);
            Transform(row, inverse);
            Array.Copy(row, 0, values, y * w, w);
        }

        var column = new Complex[h];
        for (var x = 0; x < w; x++)
        {
            for (var y = 0; y < h; y++)
            {
                column[y] = values[(y * w) + x];
            }

            Transform(column, inverse);
            for (var y = 0; y < h; y++)
            {
                values[(y * w) + x] = column[y];
            }
        }
    }

    // Matlab's convention: no scaling forward, 1/n back, so the inverse of a normalised spectrum peaks at 1 at most.
    private static void Transform(Complex[] values, bool inverse)
    {
        if (inverse)
        {
            Fourier.Inverse(values, FourierOptions.Matlab);
        }
        else
        {
            Fourier.Forward(values, FourierOptions.Matlab);
        }
    }

    private static double Vertex(double left, double middle, double right)
    {
        var denominator = left - (2 * middle) + right;
        return denominator < 0 ? Math.Clamp(0.5 * (left - right) / denominator, -0.5, 0.5) : 0;
    }

    private static Complex[] Windowed(GreyImage image, int paddedW, int paddedH)
    {
        int w = image.Width, h = image.Height;
        var mean = image.Values.Average();
        var wx = Hann(w);
        var wy = Hann(h);
        var values = new Complex[paddedW * paddedH];
        for (var y = 0; y < h; y++)
        {
            for (var x = 0; x < w; x++)
            {
                values[(y * paddedW) + x] = new Complex((image[x, y] - mean) * wx[x] * wy[y], 0);
            }
        }

        return values;
    }

    private static double[] Hann(int n)
    {
        var window = new double[n];
        for (var i = 0; i < n; i++)
        {
            window[i] = n == 1 ? 1 : 0.5 - (0.5 * Math.Cos(2 * Math.PI * i / (n - 1)));
        }

        return window;
    }
}
