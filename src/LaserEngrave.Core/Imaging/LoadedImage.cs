namespace LaserEngrave.Core.Imaging;

/// <summary>A decoded image in a compact form: packed palette indices where the file has a palette (or is grey), else RGBA.</summary>
/// <remarks>
/// Rows run top to bottom whatever the file's row order. Palette images stay at their own bit depth (a 20000 x 20000
/// 1-bit image takes 50 MB), so the mask builder can map whole bytes through the palette; greyscale files become an
/// 8-bit index into a grey palette for the same reason. Everything else is 4 bytes per pixel, capped at
/// <see cref="ImageLimits.MaxFullColourPixels"/>.
/// </remarks>
public sealed class LoadedImage
{
    private readonly byte[] _pixels;
    private readonly Rgba32[] _palette;

    private LoadedImage(ImageInfo info, int width, int height, PixelLayout layout, int bitsPerIndex, int stride, Rgba32[] palette, byte[] pixels)
    {
        if (pixels.LongLength < (long)stride * height)
        {
            throw new ArgumentException($"{pixels.LongLength} bytes is too few for {height} rows of {stride} bytes", nameof(pixels));
        }

        Info = info;
        Width = width;
        Height = height;
        Layout = layout;
        BitsPerIndex = bitsPerIndex;
        Stride = stride;
        _palette = palette;
        _pixels = pixels;
    }

    /// <summary>What the file's headers said.</summary>
    public ImageInfo Info { get; }

    public int Width { get; }

    public int Height { get; }

    public PixelLayout Layout { get; }

    /// <summary>1, 2, 4 or 8 for <see cref="PixelLayout.Indexed"/>; 0 for <see cref="PixelLayout.Rgba32"/>.</summary>
    public int BitsPerIndex { get; }

    /// <summary>Bytes per row in <see cref="Row"/>: packed indices without padding, or 4 x width.</summary>
    public int Stride { get; }

    /// <summary>The colours the indices refer to (empty for RGBA images); every index in the pixels is below its length.</summary>
    public ReadOnlySpan<Rgba32> Palette => _palette;

    /// <summary>The stored bytes of row <paramref name="y"/> (0 = top).</summary>
    public ReadOnlySpan<byte> Row(int y)
    {
        ArgumentOutOfRangeException.ThrowIfGreaterThanOrEqual((uint)y, (uint)Height, nameof(y));
        return _pixels.AsSpan((int)((long)y * Stride), Stride);
    }

    /// <summary>The colour of pixel (<paramref name="x"/>, <paramref name="y"/>), looked up through the palette when there is one.</summary>
    public Rgba32 GetPixel(int x, int y)
    {
        ArgumentOutOfRangeException.ThrowIfGreaterThanOrEqual((uint)x, (uint)Width, nameof(x));
        var row = Row(y);
        if (Layout == PixelLayout.Indexed)
        {
            return _palette[IndexedPixels.Get(row, x, BitsPerIndex)];
        }

        var p = row.Slice(x * 4, 4);
        return new Rgba32(p[0], p[1], p[2], p[3]);
    }

    /// <summary>The pixel buffer itself, for decoders that re-wrap an image (a PNG inside a BMP).</summary>
    internal byte[] PixelData => _pixels;

    internal static LoadedImage Indexed(ImageInfo info, int width, int height, int bitsPerIndex, Rgba32[] palette, byte[] pixels)
    {
        if (bitsPerIndex is not (1 or 2 or 4 or 8))
        {
            throw new ArgumentOutOfRangeException(nameof(bitsPerIndex));
        }

        if (palette.Length is 0 or > 256)
        {
            throw new ArgumentOutOfRangeException(nameof(palette), "a palette holds 1 to 256 colours");
        }

        return new LoadedImage(info, width, height, PixelLayout.Indexed, bitsPerIndex, (int)ImageLimits.IndexedStride(width, bitsPerIndex), palette, pixels);
    }

    internal static LoadedImage Rgba(ImageInfo info, int width, int height, byte[] rgba) =>
        new(info, width, height, PixelLayout.Rgba32, 0, width * 4, [], rgba);
}
