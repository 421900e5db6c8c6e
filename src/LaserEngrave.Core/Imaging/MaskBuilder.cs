namespace LaserEngrave.Core.Imaging;

/// <summary>Reduces an image to a 1-bit burn mask (1 = burn) by palette, threshold or dithering.</summary>
public static class MaskBuilder
{
    /// <summary>The mask of a decoded image under <paramref name="options"/>.</summary>
    public static BitMask Build(LoadedImage image, MaskOptions options)
    {
        ArgumentNullException.ThrowIfNull(image);
        ArgumentNullException.ThrowIfNull(options);
        options.Validate();
        return MaskOrientation.Apply(BuildUpright(image, options), options);
    }

    // The mask as the image stands; Build turns and mirrors it.
    private static BitMask BuildUpright(LoadedImage image, MaskOptions options)
    {
        var mask = new BitMask(image.Width, image.Height);
        if (image.Layout == PixelLayout.Indexed && PaletteMaskWriter.TryCreate(image.Palette, image.BitsPerIndex, options) is { } writer)
        {
            for (var y = 0; y < image.Height; y++)
            {
                writer.Write(image.Row(y), mask.Row(y), image.Width);
            }

            return mask;
        }

        if (options.Dither == DitherMethod.None)
        {
            ThresholdRgba(image, options, mask);
        }
        else
        {
            Dither(image, options, mask);
        }

        return mask;
    }

    /// <summary>
    /// Loads <paramref name="path"/> and builds its mask in one call. Uncompressed palette BMPs (the paper's 1-bit
    /// files) go straight from the file to the mask a row at a time, so a 20000 x 20000 image needs only the 50 MB mask.
    /// </summary>
    /// <exception cref="ImageLoadException">The file cannot be read or decoded.</exception>
    public static BitMask FromFile(string path, MaskOptions options, out ImageInfo info)
    {
        ArgumentNullException.ThrowIfNull(options);
        options.Validate();
        ImageInfo? found = null;
        var mask = ImageLoader.WithFile(path, reader =>
        {
            if (FormatSniffer.Detect(reader) == ImageFormat.Bmp && BmpDecoder.TryBuildMask(reader, options, out var bmpInfo) is { } direct)
            {
                found = bmpInfo;
                return MaskOrientation.Apply(direct, options);
            }

            var image = ImageLoader.Decode(reader);
            found = image.Info;
            return Build(image, options);
        });
        info = found!;
        return mask;
    }

    private static void ThresholdRgba(LoadedImage image, MaskOptions options, BitMask mask)
    {
        for (var y = 0; y < image.Height; y++)
        {
            var source = image.Row(y);
            var row = mask.Row(y);
            for (var x = 0; x < image.Width; x++)
            {
                var p = source.Slice(4 * x, 4);
                if (options.Burns(new Rgba32(p[0], p[1], p[2], p[3])))
                {
                    row[x >> 6] |= 1UL << (x & 63);
                }
            }
        }
    }

    private static void Dither(LoadedImage image, MaskOptions options, BitMask mask)
    {
        var width = image.Width;
        var luminance = new float[width];
        var transparent = new bool[width];
        var ditherer = Ditherer.Create(options.Dither, width);
        float[]? paletteLuminance = null;
        if (image.Layout == PixelLayout.Indexed)
        {
            paletteLuminance = new float[image.Palette.Length];
            for (var i = 0; i < paletteLuminance.Length; i++)
            {
                paletteLuminance[i] = (float)image.Palette[i].Luminance;
            }
        }

        for (var y = 0; y < image.Height; y++)
        {
            var source = image.Row(y);
            for (var x = 0; x < width; x++)
            {
                Rgba32 colour;
                if (paletteLuminance is not null)
                {
                    var index = IndexedPixels.Get(source, x, image.BitsPerIndex);
                    colour = image.Palette[index];
                    luminance[x] = paletteLuminance[index];
                }
                else
                {
                    colour = new Rgba32(source[4 * x], source[(4 * x) + 1], source[(4 * x) + 2], source[(4 * x) + 3]);
                    luminance[x] = (float)colour.Luminance;
                }

                transparent[x] = colour.A == 0;
            }

            var row = mask.Row(y);
            ditherer.DitherRow(y, luminance, transparent, row);
            if (options.Invert)
            {
                for (var x = 0; x < width; x++)
                {
                    if (!transparent[x])
                    {
                        row[x >> 6] ^= 1UL << (x & 63);
                    }
                }
            }
        }
    }
}
