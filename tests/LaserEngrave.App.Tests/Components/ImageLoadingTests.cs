using Bunit;
using LaserEngrave.App.Components.Workspace;
using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using Microsoft.AspNetCore.Components.Web;

namespace LaserEngrave.App.Tests.Components;

/// <summary>A big image is read and planned off the page's path: a progress line with Cancel, the last good job kept meanwhile.</summary>
public sealed class ImageLoadingTests : ComponentTest
{
    private readonly GatedImages _images = new() { GatedName = "text-banner.png" };

    [Fact]
    public async Task SlowImageOpened_ProgressShownAndTheOldJobKeptUntilTheNewOneIsPlannedOnce()
    {
        var (job, cut) = OpenQrThenRender();
        var estimate = job.EstimatedSeconds;

        var clicked = cut.Find("#samples button[data-path$='text-banner.png']").ClickAsync(new MouseEventArgs());

        cut.WaitForAssertion(() => Assert.Contains("Reading text-banner.png", cut.Find("#image-loading").TextContent, StringComparison.Ordinal));
        Assert.Contains("qr-code.bmp", cut.Find("#image-meta").TextContent, StringComparison.Ordinal);
        Assert.Contains("41 × 41 px", cut.Find("#image-meta").TextContent, StringComparison.Ordinal);
        Assert.Equal(estimate, job.EstimatedSeconds);

        _images.Gate.SetResult();
        await clicked;

        cut.WaitForAssertion(() => Assert.Contains("text-banner.png", cut.Find("#image-meta").TextContent, StringComparison.Ordinal));
        Assert.Empty(cut.FindAll("#image-loading"));
        Assert.NotEqual(estimate, job.EstimatedSeconds);
        Assert.Equal(1, _images.GatedPlans);
    }

    [Fact]
    public async Task SlowImageCancelled_OldJobStaysAndTheLineGoes()
    {
        var (job, cut) = OpenQrThenRender();
        var (estimate, version) = (job.EstimatedSeconds, job.PlanVersion);

        var clicked = cut.Find("#samples button[data-path$='text-banner.png']").ClickAsync(new MouseEventArgs());
        cut.WaitForAssertion(() => Assert.NotNull(cut.Find("#image-loading-cancel")));
        cut.Find("#image-loading-cancel").Click();
        await clicked;

        cut.WaitForAssertion(() => Assert.Empty(cut.FindAll("#image-loading")));
        _images.Gate.SetResult();
        await _images.Read.Task.WaitAsync(Xunit.TestContext.Current.CancellationToken);

        Assert.EndsWith("qr-code.bmp", job.ImagePath, StringComparison.Ordinal);
        Assert.Contains("41 × 41 px", cut.Find("#image-meta").TextContent, StringComparison.Ordinal);
        Assert.Equal((estimate, version), (job.EstimatedSeconds, job.PlanVersion));
        Assert.Equal(0, _images.GatedPlans);
    }

    [Fact]
    public async Task SlowImageThenAnotherOpenedAtOnce_TheLaterOpenWins()
    {
        var (job, _) = OpenQrThenRender();
        var drawing = TestFiles.Asset("line-drawing.png");

        var slow = job.LoadImageAsync(TestFiles.Asset("text-banner.png"), Xunit.TestContext.Current.CancellationToken);
        Assert.True(job.LoadImage(drawing));
        _images.Gate.SetResult();

        // Dropped before its plan, however far its reading got.
        Assert.False(await slow.WaitAsync(TimeSpan.FromSeconds(30), Xunit.TestContext.Current.CancellationToken));
        Assert.Equal(drawing, job.ImagePath);
        Assert.Null(job.LoadingLine);
        Assert.Equal(0, _images.GatedPlans);
    }

    [Fact]
    public async Task InvertTickedWhileReading_TheMaskFollowsIt()
    {
        var (job, _) = OpenQrThenRender();
        var banner = TestFiles.Asset("text-banner.png");

        var opening = job.LoadImageAsync(banner, Xunit.TestContext.Current.CancellationToken);
        job.Invert = true;
        _images.Gate.SetResult();

        Assert.True(await opening);
        var expected = new JobViewModel(new ImageService(), MachineProfile.Default) { Invert = true };
        Assert.True(expected.LoadImage(banner));
        Assert.Equal(expected.Mask!.CountSet(), job.Mask!.CountSet());
        var atDefault = new JobViewModel(new ImageService(), MachineProfile.Default);
        Assert.True(atDefault.LoadImage(banner));
        Assert.NotEqual(atDefault.Mask!.CountSet(), job.Mask.CountSet());
    }

    private (JobViewModel Job, IRenderedComponent<ImagePanel> Cut) OpenQrThenRender()
    {
        var job = new JobViewModel(_images, MachineProfile.Default);
        Assert.True(job.LoadImage(TestFiles.Asset("qr-code.bmp")));
        job.EditWidth(10);
        Assert.NotNull(job.EstimatedSeconds);
        return (job, Render<ImagePanel>(p => p.Add(c => c.Job, job).Add(c => c.Samples, Main.SampleImages)));
    }
}
