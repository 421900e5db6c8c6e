namespace LaserEngrave.Core.Imaging;

/// <summary>How a BMP file encodes its pixels; the header's number means different things in Windows and OS/2 v2 headers.</summary>
internal enum BmpCompression
{
    None,
    Rle8,
    Rle4,
    BitFields,
    AlphaBitFields,
    Jpeg,
    Png,
    Huffman1D,
    Rle24,
    Cmyk,
}
