using LaserEngrave.App.Services;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;

namespace LaserEngrave.App.Tests;

/// <summary>The real image service, whose reading of one file waits until the test opens <see cref="Gate"/>.</summary>
internal sealed class GatedImages : IImageService
{
    private readonly ImageService _real = new();
    private int _gatedPlans;

    public required string GatedName { get; init; }

    public TaskCompletionSource Gate { get; } = new(TaskCreationOptions.RunContinuationsAsynchronously);

    /// <summary>Set once the gated file has been read (after the gate opened).</summary>
    public TaskCompletionSource Read { get; } = new(TaskCreationOptions.RunContinuationsAsynchronously);

    public int GatedPlans => Volatile.Read(ref _gatedPlans);

    public LoadedImage Load(string path)
    {
        if (Path.GetFileName(path) != GatedName)
        {
            return _real.Load(path);
        }

        Gate.Task.Wait(Xunit.TestContext.Current.CancellationToken);
        var image = _real.Load(path);
        Read.TrySetResult();
        return image;
    }

    public BitMask BuildMask(LoadedImage image, MaskOptions options) => _real.BuildMask(image, options);

    public PreparedJob Prepare(JobSpec spec, ImageInfo info, BitMask mask)
    {
        if (Path.GetFileName(spec.ImagePath) == GatedName)
        {
            Interlocked.Increment(ref _gatedPlans);
        }

        return _real.Prepare(spec, info, mask);
    }

    public byte[] RenderOriginalPng(LoadedImage image, int maxSidePx) => _real.RenderOriginalPng(image, maxSidePx);

    public byte[] RenderMaskPng(BitMask mask, int maxSidePx) => _real.RenderMaskPng(mask, maxSidePx);
}
