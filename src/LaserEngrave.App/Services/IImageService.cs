using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;

namespace LaserEngrave.App.Services;

/// <summary>Images, masks, plans and their pictures for the page: Core's loaders, MaskBuilder and PreparedJob behind one seam.</summary>
public interface IImageService
{
    /// <summary>Decodes an image file; throws <see cref="ImageLoadException"/> naming the file and the problem.</summary>
    LoadedImage Load(string path);

    /// <summary>Thresholds or dithers the image into the mask of pixels to burn.</summary>
    BitMask BuildMask(LoadedImage image, MaskOptions options);

    /// <summary>Sizes, places and plans a mask; throws one-line Core errors for unusable values.</summary>
    PreparedJob Prepare(JobSpec spec, ImageInfo info, BitMask mask);

    /// <summary>The image as a PNG no larger than <paramref name="maxSidePx"/> on its longer side.</summary>
    byte[] RenderOriginalPng(LoadedImage image, int maxSidePx);

    /// <summary>The mask as a PNG (black = burn) no larger than <paramref name="maxSidePx"/> on its longer side.</summary>
    byte[] RenderMaskPng(BitMask mask, int maxSidePx);
}
