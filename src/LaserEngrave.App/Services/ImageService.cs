using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.IO;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Preview;

namespace LaserEngrave.App.Services;

/// <summary>The real <see cref="IImageService"/> over Core.</summary>
public sealed class ImageService : IImageService
{
    /// <remarks>Only regular files are opened: a FIFO would block the request that opens it for ever.</remarks>
    public LoadedImage Load(string path) =>
        RegularFile.Problem(path) is { } problem ? throw new ImageLoadException(path, problem) : ImageLoader.Load(path);

    public BitMask BuildMask(LoadedImage image, MaskOptions options) => MaskBuilder.Build(image, options);

    public PreparedJob Prepare(JobSpec spec, ImageInfo info, BitMask mask) => PreparedJob.Prepare(spec, info, mask);

    public byte[] RenderOriginalPng(LoadedImage image, int maxSidePx)
    {
        ArgumentNullException.ThrowIfNull(image);
        // Never enlarged: the page scales small images up itself, without smoothing.
        var size = PreviewSize.Fit(image.Width, image.Height, Math.Min(maxSidePx, Math.Max(image.Width, image.Height)));
        var rgba = new byte[size.Width * size.Height * 4];

        // Nearest-neighbour sampling: a preview of a 1-bit mask must stay sharp, not blurred into greys.
        for (var y = 0; y < size.Height; y++)
        {
            var sourceY = (int)((long)y * image.Height / size.Height);
            for (var x = 0; x < size.Width; x++)
            {
                var pixel = image.GetPixel((int)((long)x * image.Width / size.Width), sourceY);
                var i = ((y * size.Width) + x) * 4;
                rgba[i] = pixel.R;
                rgba[i + 1] = pixel.G;
                rgba[i + 2] = pixel.B;
                rgba[i + 3] = pixel.A;
            }
        }

        using var output = new MemoryStream();
        PngWriter.WriteRgba(output, size.Width, size.Height, rgba);
        return output.ToArray();
    }

    public byte[] RenderMaskPng(BitMask mask, int maxSidePx)
    {
        using var output = new MemoryStream();
        MaskPreview.Render(mask, output, Math.Min(maxSidePx, Math.Max(mask.Width, mask.Height)));
        return output.ToArray();
    }
}
