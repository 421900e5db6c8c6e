namespace LaserEngrave.Simulator.Camera;

/// <summary>The twin's sample surface: a seeded, continuous grain (value noise in three sizes), the same wherever and however often it is looked at.</summary>
/// <remarks>
/// Continuous in µm, so a stage move of a fraction of a camera pixel moves the image by that fraction, as on a real
/// sample; sizes of 4, 12 and 40 µm give a camera of 0.5..5 µm per pixel something to track at every scale.
/// </remarks>
public sealed class SampleTexture
{
    private static readonly (double CellUm, double Weight)[] Octaves = [(40, 0.5), (12, 0.3), (4, 0.2)];
    private readonly ulong _seed;

    public SampleTexture(int seed)
    {
        _seed = (ulong)(uint)seed * 0x9E3779B97F4A7C15UL;
    }

    /// <summary>Brightness at (<paramref name="xUm"/>, <paramref name="yUm"/>) on the sample, 0..1.</summary>
    public double At(double xUm, double yUm)
    {
        var sum = 0.0;
        for (var o = 0; o < Octaves.Length; o++)
        {
            var (cell, weight) = Octaves[o];
            sum += weight * Noise(xUm / cell, yUm / cell, (ulong)o);
        }

        return sum;
    }

    /// <summary>
    /// Fills <paramref name="into"/> (<paramref name="w"/> x <paramref name="h"/>, row by row) with the brightness at the
    /// sample points (x0 + xPerU u + xPerV v, y0 + yPerU u + yPerV v): the same values as <see cref="At"/> point by point.
    /// </summary>
    /// <remarks>
    /// A camera frame needs this for every pixel, and hashing four lattice points per pixel and octave made frames cost
    /// tens of milliseconds; each octave's lattice over the frame's footprint is hashed once here, and the points step
    /// along each row by addition.
    /// </remarks>
    public void Fill(double[] into, int w, int h, double x0, double y0, double xPerU, double yPerU, double xPerV, double yPerV)
    {
        ArgumentNullException.ThrowIfNull(into);
        if (into.Length < w * h)
        {
            throw new ArgumentException($"{into.Length} values cannot hold a {w} x {h} image", nameof(into));
        }

        Array.Clear(into, 0, w * h);
        double[] xs = [x0, x0 + (xPerU * (w - 1)), x0 + (xPerV * (h - 1)), x0 + (xPerU * (w - 1)) + (xPerV * (h - 1))];
        double[] ys = [y0, y0 + (yPerU * (w - 1)), y0 + (yPerV * (h - 1)), y0 + (yPerU * (w - 1)) + (yPerV * (h - 1))];
        for (var o = 0; o < Octaves.Length; o++)
        {
            var (cell, weight) = Octaves[o];
            var i0 = (long)Math.Floor(xs.Min() / cell) - 1;
            var j0 = (long)Math.Floor(ys.Min() / cell) - 1;
            var gw = (int)((long)Math.Floor(xs.Max() / cell) + 2 - i0 + 1);
            var gh = (int)((long)Math.Floor(ys.Max() / cell) + 2 - j0 + 1);
            var lattice = new double[gw * gh];
            for (var j = 0; j < gh; j++)
            {
                for (var i = 0; i < gw; i++)
                {
                    lattice[(j * gw) + i] = Lattice(i0 + i, j0 + j, (ulong)o);
                }
            }

            // In cell units, relative to the lattice's corner, so the floor is a plain truncation of a positive number.
            var (ax, ay) = (xPerU / cell, yPerU / cell);
            for (var v = 0; v < h; v++)
            {
                var x = ((x0 + (xPerV * v)) / cell) - i0;
                var y = ((y0 + (yPerV * v)) / cell) - j0;
                var row = v * w;
                for (var u = 0; u < w; u++, x += ax, y += ay)
                {
                    var ix = (int)x;
                    var iy = (int)y;
                    var fx = x - ix;
                    var fy = y - iy;
                    fx = fx * fx * fx * ((fx * ((fx * 6) - 15)) + 10);
                    fy = fy * fy * fy * ((fy * ((fy * 6) - 15)) + 10);
                    var k = (iy * gw) + ix;
                    var top = lattice[k] + ((lattice[k + 1] - lattice[k]) * fx);
                    var bottom = lattice[k + gw] + ((lattice[k + gw + 1] - lattice[k + gw]) * fx);
                    into[row + u] += weight * (top + ((bottom - top) * fy));
                }
            }
        }
    }

    private double Noise(double x, double y, ulong octave)
    {
        var ix = Math.Floor(x);
        var iy = Math.Floor(y);
        var fx = Fade(x - ix);
        var fy = Fade(y - iy);
        var (i, j) = ((long)ix, (long)iy);
        var top = Lerp(Lattice(i, j, octave), Lattice(i + 1, j, octave), fx);
        var bottom = Lerp(Lattice(i, j + 1, octave), Lattice(i + 1, j + 1, octave), fx);
        return Lerp(top, bottom, fy);
    }

    // A value 0..1 per lattice point from a 64-bit mix (splitmix64's finaliser): no table, so the sample has no edge.
    private double Lattice(long i, long j, ulong octave)
    {
        var z = _seed ^ ((ulong)i * 0xBF58476D1CE4E5B9UL) ^ ((ulong)j * 0x94D049BB133111EBUL) ^ (octave * 0xD6E8FEB86659FD93UL);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9UL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBUL;
        z ^= z >> 31;
        return (z >> 11) * (1.0 / (1UL << 53));
    }

    private static double Fade(double t) => t * t * t * ((t * ((t * 6) - 15)) + 10);

    private static double Lerp(double a, double b, double t) => a + ((b - a) * t);
}
