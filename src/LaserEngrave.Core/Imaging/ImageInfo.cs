namespace LaserEngrave.Core.Imaging;

/// <summary>What an image file's headers say about it, read without decoding its pixels.</summary>
/// <param name="Path">The file as given by the caller.</param>
/// <param name="Format">The container format.</param>
/// <param name="BitsPerPixel">Bits per stored pixel (all channels, e.g. 1, 8, 24, 32; 64 for 16-bit RGBA PNG).</param>
/// <param name="PaletteSize">Colours in the palette the pixels index; 0 when the pixels hold colours directly.</param>
/// <param name="Width">Width in pixels.</param>
/// <param name="Height">Height in pixels.</param>
/// <param name="FileSizeBytes">Size of the file.</param>
/// <param name="DpiX">Horizontal resolution in dots per inch when the file states one (BMP pels per metre, PNG pHYs in metres).</param>
/// <param name="DpiY">Vertical resolution in dots per inch when the file states one.</param>
/// <param name="RowOrder">Whether the file stores the top or the bottom row first.</param>
/// <param name="Compression">The pixel encoding, e.g. "none", "RLE8", "RLE4", "BITFIELDS", "deflate", "LZW", "ASCII".</param>
/// <param name="HasAlpha">Whether the file declares transparency: an alpha channel or mask, or a transparent colour (RLE BMP and GIF canvas gaps and TIFF extra alpha samples are transparent too, found only when decoding).</param>
/// <param name="Interlaced">Whether rows are stored interlaced (PNG Adam7, GIF, progressive JPEG).</param>
/// <param name="FrameCount">Pages or frames in the file where the decoder counts them (JPEG, TIFF, WebP; at most <see cref="MaxFramesCounted"/>), null where it does not; only the first is ever decoded.</param>
public sealed record ImageInfo(
    string Path,
    ImageFormat Format,
    int BitsPerPixel,
    int PaletteSize,
    int Width,
    int Height,
    long FileSizeBytes,
    double? DpiX,
    double? DpiY,
    RowOrder RowOrder,
    string Compression,
    bool HasAlpha,
    bool Interlaced = false,
    int? FrameCount = null)
{
    /// <summary>Most pages or frames counted for <see cref="FrameCount"/>; a file with more reports this many.</summary>
    public const int MaxFramesCounted = 1000;

    /// <summary>Inches per metre, to turn BMP's and PNG's pixels per metre into dots per inch.</summary>
    public const double MetresPerInch = 0.0254;

    /// <summary>Dots per inch from pixels per metre; null when the value says nothing (zero or negative).</summary>
    public static double? DpiFromPixelsPerMetre(long pixelsPerMetre) => pixelsPerMetre > 0 ? pixelsPerMetre * MetresPerInch : null;

    /// <summary>Whether the file holds pages or frames beyond the first, which are not decoded.</summary>
    public bool HasMoreFrames => FrameCount > 1;
}
