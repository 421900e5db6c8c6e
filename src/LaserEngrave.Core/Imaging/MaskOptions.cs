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

    /// <summary>
    /// Quarter turns clockwise, 0..3, as the image is seen on the stage (row 0 at the top), applied after
    /// <see cref="MirrorX"/> and <see cref="MirrorY"/>: the mask is turned, so the plan, the preview and the burn follow it.
    /// </summary>
    public int QuarterTurns { get; init; }

    /// <summary>The image flipped left to right (its columns reversed) before it is turned.</summary>
    public bool MirrorX { get; init; }

    /// <summary>The image flipped top to bottom (its rows reversed) before it is turned.</summary>
    public bool MirrorY { get; init; }

    /// <summary>Whether the mask is turned or mirrored at all.</summary>
    public bool Transforms => QuarterTurns != 0 || MirrorX || MirrorY;

    /// <summary>Throws <see cref="ArgumentOutOfRangeException"/> for a threshold outside 0..100, an unknown dither or quarter turns outside 0..3.</summary>
    public void Validate()
    {
        if (QuarterTurns is < 0 or > 3)
        {
            throw new ArgumentOutOfRangeException(nameof(QuarterTurns), QuarterTurns, "quarter turns must be 0, 1, 2 or 3 (0°, 90°, 180°, 270° clockwise)");
        }

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
