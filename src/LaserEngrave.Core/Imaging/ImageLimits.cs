namespace LaserEngrave.Core.Imaging;

/// <summary>The largest images the decoders accept, checked before anything is allocated from a header's claim.</summary>
public static class ImageLimits
{
    /// <summary>Most bytes a decoded image may take (1 GiB).</summary>
    public const long MaxDecodedBytes = 1L << 30;

    /// <summary>Most pixels of an image decoded to full colour (4 bytes each, so 1 GiB); palette images may be larger.</summary>
    public const long MaxFullColourPixels = 256L * 1024 * 1024;

    /// <summary>Refuses sizes a mask cannot hold (zero, negative, wider or taller than <see cref="BitMask.MaxSide"/>, more than <see cref="BitMask.MaxPixels"/>).</summary>
    internal static void CheckDimensions(string path, long width, long height)
    {
        if (width <= 0 || height <= 0)
        {
            throw new ImageLoadException(path, $"image size {width} x {height} pixels is not positive");
        }

        if (width > BitMask.MaxSide || height > BitMask.MaxSide || width * height > BitMask.MaxPixels)
        {
            throw new ImageLoadException(
                path,
                $"image size {width} x {height} pixels is larger than the limit ({BitMask.MaxSide} pixels per side, {BitMask.MaxPixels / 1_000_000} megapixels in all)");
        }
    }

    /// <summary>Refuses palette images whose packed indices would exceed <see cref="MaxDecodedBytes"/>.</summary>
    internal static void CheckIndexed(string path, long width, long height, int bitsPerIndex)
    {
        CheckDimensions(path, width, height);
        var bytes = IndexedStride(width, bitsPerIndex) * height;
        if (bytes > MaxDecodedBytes)
        {
            throw new ImageLoadException(
                path,
                $"a {width} x {height} image at {bitsPerIndex} bits per pixel needs {bytes >> 20} MB decoded, more than the {MaxDecodedBytes >> 20} MB limit");
        }
    }

    /// <summary>Refuses full-colour images above <see cref="MaxFullColourPixels"/>.</summary>
    internal static void CheckFullColour(string path, long width, long height)
    {
        CheckDimensions(path, width, height);
        if (width * height > MaxFullColourPixels)
        {
            throw new ImageLoadException(
                path,
                $"a {width} x {height} full-colour image ({width * height / 1_000_000} megapixels) is more than the {MaxFullColourPixels >> 20}-megapixel limit for full-colour decoding; save it as a 1-bit or 8-bit palette image");
        }
    }

    /// <summary>Bytes per row of packed indices.</summary>
    internal static long IndexedStride(long width, int bitsPerIndex) => ((width * bitsPerIndex) + 7) >> 3;
}
