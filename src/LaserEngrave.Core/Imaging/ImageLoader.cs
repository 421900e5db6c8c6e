namespace LaserEngrave.Core.Imaging;

/// <summary>Reads image headers and decodes images (BMP, PNG, GIF, Netpbm), refusing bad files with one clear line.</summary>
/// <remarks>
/// The decoders are our own because SixLabors.ImageSharp is not on this machine's package source. JPEG, TIFF and WebP
/// are recognised and refused with a message saying to save the image as PNG or BMP.
/// </remarks>
public static class ImageLoader
{
    /// <summary>What the file's headers say, without decoding its pixels.</summary>
    /// <exception cref="ImageLoadException">The file cannot be read or its headers are bad.</exception>
    public static ImageInfo ReadInfo(string path) => WithFile(path, ReadInfo);

    /// <summary>What a seekable stream's headers say; <paramref name="name"/> names it in errors.</summary>
    public static ImageInfo ReadInfo(Stream stream, string name) => WithStream(stream, name, ReadInfo);

    /// <summary>Decodes the whole image (for GIF, its first frame).</summary>
    /// <exception cref="ImageLoadException">The file cannot be read or decoded.</exception>
    public static LoadedImage Load(string path) => WithFile(path, Decode);

    /// <summary>Decodes an image from a seekable stream; <paramref name="name"/> names it in errors.</summary>
    public static LoadedImage Load(Stream stream, string name) => WithStream(stream, name, Decode);

    internal static ImageInfo ReadInfo(ImageReader reader) => FormatSniffer.Detect(reader) switch
    {
        ImageFormat.Bmp => BmpDecoder.ReadInfo(reader),
        ImageFormat.Png => PngDecoder.ReadInfo(reader),
        ImageFormat.Gif => GifDecoder.ReadInfo(reader),
        _ => NetpbmDecoder.ReadInfo(reader),
    };

    internal static LoadedImage Decode(ImageReader reader) => FormatSniffer.Detect(reader) switch
    {
        ImageFormat.Bmp => BmpDecoder.Decode(reader),
        ImageFormat.Png => PngDecoder.Decode(reader),
        ImageFormat.Gif => GifDecoder.Decode(reader),
        _ => NetpbmDecoder.Decode(reader),
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
