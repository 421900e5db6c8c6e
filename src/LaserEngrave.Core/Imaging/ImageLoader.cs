namespace LaserEngrave.Core.Imaging;

/// <summary>Reads image headers and decodes images (BMP, PNG, GIF, Netpbm, JPEG, TIFF, WebP), refusing bad files with one clear line.</summary>
/// <remarks>
/// BMP, PNG, GIF and Netpbm use our own decoders: SixLabors.ImageSharp is not on this machine's package source, and ours
/// match the whole BMP suite where ImageMagick does not (docs/dependencies.md). JPEG, TIFF and WebP go through
/// ImageMagick (<see cref="MagickDecoder"/>), under the same size limits.
/// </remarks>
public static class ImageLoader
{
    /// <summary>What the file's headers say, without decoding its pixels.</summary>
    /// <exception cref="ImageLoadException">The file cannot be read or its headers are bad.</exception>
    public static ImageInfo ReadInfo(string path) => WithFile(path, ReadInfo);

    /// <summary>
    /// What the file's headers say, after reading every pixel once: a file whose pixel data is cut short or corrupt is
    /// refused here, as building its mask would refuse it, and not passed as if it were whole.
    /// </summary>
    /// <exception cref="ImageLoadException">The file cannot be read, its headers are bad or its pixel data is.</exception>
    public static ImageInfo ReadInfoVerified(string path)
    {
        var info = ReadInfo(path);
        _ = MaskBuilder.FromFile(path, MaskOptions.Default, out _);
        return info;
    }

    /// <summary>What a seekable stream's headers say; <paramref name="name"/> names it in errors.</summary>
    public static ImageInfo ReadInfo(Stream stream, string name) => WithStream(stream, name, ReadInfo);

    /// <summary>Decodes the whole image (for GIF and WebP, its first frame; for TIFF, its first page).</summary>
    /// <exception cref="ImageLoadException">The file cannot be read or decoded.</exception>
    public static LoadedImage Load(string path) => WithFile(path, Decode);

    /// <summary>Decodes an image from a seekable stream; <paramref name="name"/> names it in errors.</summary>
    public static LoadedImage Load(Stream stream, string name) => WithStream(stream, name, Decode);

    internal static ImageInfo ReadInfo(ImageReader reader) => FormatSniffer.Detect(reader) switch
    {
        ImageFormat.Bmp => BmpDecoder.ReadInfo(reader),
        ImageFormat.Png => PngDecoder.ReadInfo(reader),
        ImageFormat.Gif => GifDecoder.ReadInfo(reader),
        ImageFormat.Pbm or ImageFormat.Pgm or ImageFormat.Ppm => NetpbmDecoder.ReadInfo(reader),
        var other => MagickDecoder.ReadInfo(reader, other),
    };

    internal static LoadedImage Decode(ImageReader reader) => FormatSniffer.Detect(reader) switch
    {
        ImageFormat.Bmp => BmpDecoder.Decode(reader),
        ImageFormat.Png => PngDecoder.Decode(reader),
        ImageFormat.Gif => GifDecoder.Decode(reader),
        ImageFormat.Pbm or ImageFormat.Pgm or ImageFormat.Ppm => NetpbmDecoder.Decode(reader),
        var other => MagickDecoder.Decode(reader, other),
    };

    /// <summary>Opens <paramref name="path"/>, runs <paramref name="action"/>, and turns every I/O failure into an <see cref="ImageLoadException"/>.</summary>
    internal static T WithFile<T>(string path, Func<ImageReader, T> action)
    {
        ArgumentException.ThrowIfNullOrEmpty(path);
        return Guard(path, () =>
        {
            using var reader = ImageReader.Open(path);
            return action(reader);
        });
    }

    private static T WithStream<T>(Stream stream, string name, Func<ImageReader, T> action)
    {
        ArgumentNullException.ThrowIfNull(stream);
        ArgumentException.ThrowIfNullOrEmpty(name);
        return Guard(name, () =>
        {
            if (stream.CanSeek)
            {
                using var reader = new ImageReader(stream, name, ownsStream: false);
                return action(reader);
            }

            // Decoders seek (BMP rows, PNG chunk scans), so a forward-only stream is copied first.
            using var copy = new MemoryStream();
            stream.CopyTo(copy);
            copy.Position = 0;
            using var copied = new ImageReader(copy, name, ownsStream: false);
            return action(copied);
        });
    }

    private static T Guard<T>(string path, Func<T> action)
    {
        try
        {
            return action();
        }
        catch (FileNotFoundException ex)
        {
            throw new ImageLoadException(path, "file not found", ex);
        }
        catch (DirectoryNotFoundException ex)
        {
            throw new ImageLoadException(path, "folder not found", ex);
        }
        catch (UnauthorizedAccessException ex)
        {
            throw new ImageLoadException(path, "access denied", ex);
        }
        catch (InvalidDataException ex)
        {
            throw new ImageLoadException(path, $"the compressed image data is corrupt ({ex.Message})", ex);
        }
        catch (EndOfStreamException ex)
        {
            throw new ImageLoadException(path, "the file is truncated", ex);
        }
        catch (IOException ex)
        {
            throw new ImageLoadException(path, $"cannot be read ({ex.Message})", ex);
        }
    }
}
