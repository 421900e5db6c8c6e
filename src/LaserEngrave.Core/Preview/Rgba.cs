namespace LaserEngrave.Core.Preview;

/// <summary>An 8-bit-per-channel colour.</summary>
public readonly record struct Rgba(byte R, byte G, byte B, byte A = 255)
{
    /// <summary>The colour a fraction <paramref name="t"/> (0..1) of the way from <paramref name="from"/> to <paramref name="to"/>.</summary>
    public static Rgba Lerp(Rgba from, Rgba to, double t)
    {
        t = Math.Clamp(t, 0, 1);
        return new Rgba(Mix(from.R, to.R), Mix(from.G, to.G), Mix(from.B, to.B), Mix(from.A, to.A));

        byte Mix(byte a, byte b) => (byte)Math.Round(a + ((b - a) * t));
    }
}
