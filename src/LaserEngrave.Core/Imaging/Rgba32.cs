namespace LaserEngrave.Core.Imaging;

/// <summary>One colour with 8-bit red, green, blue and alpha (255 = opaque), not premultiplied.</summary>
public readonly record struct Rgba32(byte R, byte G, byte B, byte A = 255)
{
    /// <summary>Rec. 709 luma weights times 10000, so white sums to exactly <see cref="WhiteLuma"/>.</summary>
    private const int RedWeight = 2126;
    private const int GreenWeight = 7152;
    private const int BlueWeight = 722;

    /// <summary>The integer luma of white.</summary>
    public const int WhiteLuma = 255 * 10000;

    public static Rgba32 Black => new(0, 0, 0);

    public static Rgba32 White => new(255, 255, 255);

    public static Rgba32 Transparent => new(0, 0, 0, 0);

    /// <summary>
    /// Rec. 709 luma of the stored (gamma-encoded) values, composited over white, scaled so black is 0 and white 1.
    /// </summary>
    /// <remarks>
    /// Compositing over white is what a viewer on a white page shows, and it makes a fully transparent pixel white.
    /// Integer weights keep pure black and pure white exactly 0 and 1, which the mask builder relies on.
    /// </remarks>
    public double Luminance
    {
        get
        {
            var luma = (RedWeight * R) + (GreenWeight * G) + (BlueWeight * B);
            if (A == 255)
            {
                return luma / (double)WhiteLuma;
            }

            return ((long)luma * A + ((long)WhiteLuma * (255 - A))) / (255.0 * WhiteLuma);
        }
    }

    /// <summary>Integer Rec. 709 luma (0..<see cref="WhiteLuma"/>) of the opaque colour, ignoring alpha.</summary>
    public static int Luma(byte r, byte g, byte b) => (RedWeight * r) + (GreenWeight * g) + (BlueWeight * b);
}
