namespace LaserEngrave.Core.Imaging;

/// <summary>The file formats LaserEngrave decodes.</summary>
public enum ImageFormat
{
    Bmp,
    Png,
    Gif,

    /// <summary>Netpbm bitmap (P1 ASCII, P4 binary).</summary>
    Pbm,

    /// <summary>Netpbm greymap (P2 ASCII, P5 binary).</summary>
    Pgm,

    /// <summary>Netpbm pixmap (P3 ASCII, P6 binary).</summary>
    Ppm,
}
