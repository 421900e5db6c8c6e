namespace LaserEngrave.Core.Imaging;

/// <summary>How an image becomes a burn mask.</summary>
/// <remarks>
/// Luminance is Rec. 709 luma of the stored values composited over white (<see cref="Rgba32.Luminance"/>), 0 = black, 1 = white.
/// Without dithering a pixel burns when its luminance is below <see cref="ThresholdPercent"/> % of white. The dithers
/// quantise at mid-grey and ignore the threshold, because a threshold would only shift their grey levels.
/// Fully transparent pixels never burn, with or without <see cref="Invert"/>.
/// </remarks>
public sealed record MaskOptions
{
    /// <summary>The defaults: threshold 50 %, no dithering, no inversion.</summary>
    public static MaskOptions Default { get; } = new();

    /// <summary>Luminance (percent of white) below which a pixel burns; 0 burns nothing, 100 burns everything but pure white.</summary>
    public double ThresholdPercent { get; init; } = 50;

    public DitherMethod Dither { get; init; } = DitherMethod.None;

    /// <summary>Burns the opaque pixels that would not burn, and spares those that would.</summary>
    public bool Invert { get; init; }

    /// <summary>Throws <see cref="ArgumentOutOfRangeException"/> for a threshold outside 0..100 or an unknown dither.</summary>
    public void Validate()
    {
        if (!(ThresholdPercent >= 0 && ThresholdPercent <= 100))
        {
            throw new ArgumentOutOfRangeException(nameof(ThresholdPercent), ThresholdPercent, "the threshold must be between 0 and 100 %");
        }

        if (!Enum.IsDefined(Dither))
        {
            throw new ArgumentOutOfRangeException(nameof(Dither), Dither, "unknown dither method");
        }
    }

    /// <summary>Whether an opaque colour burns under plain thresholding (before <see cref="Invert"/>).</summary>
    internal bool IsDark(Rgba32 colour) => colour.Luminance < ThresholdPercent / 100.0;

    /// <summary>Whether a colour burns under plain thresholding, with transparency and <see cref="Invert"/> applied.</summary>
    internal bool Burns(Rgba32 colour) => colour.A != 0 && (IsDark(colour) ^ Invert);
}
