using LaserEngrave.Core.Preview;
using LaserEngrave.Core.Tests.Planning;

namespace LaserEngrave.Core.Tests.Preview;

public class MaskPreviewTests
{
    [Fact]
    public void RenderGray_Upscaled_EveryMaskPixelBecomesASharpBlock()
    {
        var mask = TestMasks.FromRows("#.", ".#");
        var gray = MaskPreview.RenderGray(mask, 4, 4);
        byte[] expected =
        [
            0, 0, 255, 255,
            0, 0, 255, 255,
            255, 255, 0, 0,
            255, 255, 0, 0,
        ];
        Assert.Equal(expected, gray);
    }

    [Fact]
    public void RenderGray_Downscaled_SamplesThePixelUnderEachCentre()
    {
        // 6 columns into 3: preview pixel x shows mask column 2x + 1.
        var mask = TestMasks.FromRows(".#.#..");
        Assert.Equal([0, 0, 255], MaskPreview.RenderGray(mask, 3, 1));
    }

    [Fact]
    public void Render_MaxSide_KeepsTheAspectAndWritesThePixels()
    {
        var mask = TestMasks.Random(new Random(3), 41, 20);
        using var png = new MemoryStream();
        MaskPreview.Render(mask, png, maxSidePx: 410);

        var (width, height, channels, pixels) = PngFile.Read(png.ToArray());
        Assert.Equal((410, 200, 1), (width, height, channels));
        Assert.Equal(MaskPreview.RenderGray(mask, 410, 200), pixels);
        for (var y = 0; y < mask.Height; y++)
        {
            for (var x = 0; x < mask.Width; x++)
            {
                Assert.Equal(mask[x, y] ? 0 : 255, pixels[(((10 * y) + 5) * 410) + (10 * x) + 5]);
            }
        }
    }

    [Theory]
    [InlineData(0, 10)]
    [InlineData(10, MaskPreview.MaxSidePx + 1)]
    public void RenderGray_UnusableSize_Throws(int width, int height)
    {
        Assert.Throws<ArgumentOutOfRangeException>(() => MaskPreview.RenderGray(TestMasks.FromRows("#"), width, height));
    }

    [Theory]
    [InlineData(41, 41, 820, 820, 820)]
    [InlineData(200, 100, 50, 50, 25)]
    [InlineData(1, 1000, 100, 1, 100)]
    public void Fit_LongerSideBecomesTheMaximum(int width, int height, int maxSide, int expectedWidth, int expectedHeight)
    {
        Assert.Equal(new PreviewSize(expectedWidth, expectedHeight), PreviewSize.Fit(width, height, maxSide));
    }
}
