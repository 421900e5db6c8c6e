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
