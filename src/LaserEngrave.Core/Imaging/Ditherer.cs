namespace LaserEngrave.Core.Imaging;

/// <summary>Turns rows of luminance (0 = black, 1 = white) into burn bits, row after row from the top.</summary>
internal abstract class Ditherer
{
    public static Ditherer Create(DitherMethod method, int width) => method switch
    {
        DitherMethod.FloydSteinberg => new ErrorDiffusionDitherer(width, ErrorDiffusionDitherer.FloydSteinberg),
        DitherMethod.Atkinson => new ErrorDiffusionDitherer(width, ErrorDiffusionDitherer.Atkinson),
        DitherMethod.Bayer => new BayerDitherer(),
        _ => throw new ArgumentOutOfRangeException(nameof(method), method, "not a dither method"),
    };

    /// <summary>Sets the bits of the pixels that burn; transparent pixels never burn and pass on no error.</summary>
    public abstract void DitherRow(int y, ReadOnlySpan<float> luminance, ReadOnlySpan<bool> transparent, Span<ulong> maskRow);
}
