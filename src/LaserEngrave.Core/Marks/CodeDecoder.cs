using LaserEngrave.Core.Imaging;
using ZXing;
using ZXing.Common;

namespace LaserEngrave.Core.Marks;

/// <summary>Reads a code back from a picture with ZXing, as a scanner would.</summary>
public static class CodeDecoder
{
    /// <summary>The text of the code of <paramref name="kind"/> in <paramref name="mask"/> (set = dark), or null when it does not read.</summary>
    /// <param name="mask">The picture; it should carry its quiet zone.</param>
    /// <param name="scale">Pixels a mask pixel: ZXing wants a few pixels a module.</param>
    public static string? Decode(BitMask mask, CodeKind kind, int scale = 1)
    {
        ArgumentNullException.ThrowIfNull(mask);
        ArgumentOutOfRangeException.ThrowIfLessThan(scale, 1);
        var width = mask.Width * scale;
        var height = mask.Height * scale;
        var grey = new byte[(long)width * height];
        for (var y = 0; y < height; y++)
        {
            for (var x = 0; x < width; x++)
            {
                grey[((long)y * width) + x] = mask[x / scale, y / scale] ? (byte)0 : (byte)255;
            }
        }

        return Decode(grey, width, height, kind);
    }

    /// <summary>The text of the code in an 8-bit grey picture (0 = black), or null when it does not read.</summary>
    public static string? Decode(byte[] grey, int width, int height, CodeKind kind)
    {
        ArgumentNullException.ThrowIfNull(grey);
        var reader = new BarcodeReaderGeneric
        {
            Options = new DecodingOptions
            {
                PossibleFormats = [kind == CodeKind.Qr ? BarcodeFormat.QR_CODE : BarcodeFormat.DATA_MATRIX],
                TryHarder = true,
            },
        };
        return reader.Decode(new RGBLuminanceSource(grey, width, height, RGBLuminanceSource.BitmapFormat.Gray8))?.Text;
    }
}
