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

    /// <summary>JPEG (JFIF, EXIF), decoded through ImageMagick.</summary>
    Jpeg,

    /// <summary>TIFF and BigTIFF, first page only, decoded through ImageMagick.</summary>
    Tiff,

    /// <summary>WebP, lossy or lossless, first frame only, decoded through ImageMagick.</summary>
    WebP,
}
