namespace LaserEngrave.Core.Imaging;

/// <summary>How grey levels become a pattern of burnt and unburnt pixels.</summary>
public enum DitherMethod
{
    /// <summary>No dithering: a pixel burns when its luminance is below the threshold.</summary>
    None,

    /// <summary>Floyd–Steinberg error diffusion (7/16 right, 3/16, 5/16, 1/16 on the next row).</summary>
    FloydSteinberg,

    /// <summary>Atkinson error diffusion: 1/8 of the error to six neighbours, so 1/4 is dropped and contrast kept.</summary>
    Atkinson,

    /// <summary>Ordered dithering with the 8 x 8 Bayer matrix: deterministic and free of error streaks.</summary>
    Bayer,
}
