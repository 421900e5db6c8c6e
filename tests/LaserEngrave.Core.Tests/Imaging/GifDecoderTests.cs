using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Tests.Imaging;

public class GifDecoderTests
{
    private static Rgba32[] Palette(int count, int seed)
    {
        var random = new Random(seed);
        return Enumerable.Range(0, count).Select(_ => new Rgba32((byte)random.Next(256), (byte)random.Next(256), (byte)random.Next(256))).ToArray();
    }

    [Theory]
    [InlineData(2, 7, 5)]
    [InlineData(4, 40, 30)]
    [InlineData(16, 200, 150)]
    [InlineData(256, 123, 77)]
    public void Load_RandomIndices_RoundTripThroughLzw(int colours, int width, int height)
    {
        // Big random images fill the 4096-entry table, so the encoder's clear codes and 12-bit codes are decoded too.
        var random = new Random(colours + width);
        var indices = Enumerable.Range(0, width * height).Select(_ => (byte)random.Next(colours)).ToArray();
        var palette = Palette(colours, colours);
        var file = new TestGif { ScreenWidth = width, ScreenHeight = height, FrameWidth = width, FrameHeight = height, Indices = indices, GlobalPalette = palette }.ToBytes();

        var image = ImageAssert.Load(file);

        ImageAssert.PixelsEqual((x, y) => palette[indices[(y * width) + x]], image);
        Assert.Equal(new ImageInfo("test-image", ImageFormat.Gif, Math.Max(1, (int)Math.Log2(colours)), colours, width, height, file.Length, null, null, RowOrder.TopDown, "LZW", false), image.Info);
    }

    [Fact]
    public void Load_LongRuns_DecodeTheCodeDefinedByItsOwnUse()
    {
        // A constant image makes the encoder emit codes the moment it defines them (the KwKwK case).
        var indices = new byte[5000];
        var file = new TestGif { ScreenWidth = 100, ScreenHeight = 50, FrameWidth = 100, FrameHeight = 50, Indices = indices, GlobalPalette = [Rgba32.Black, Rgba32.White] }.ToBytes();

        var image = ImageAssert.Load(file);

        ImageAssert.PixelsEqual((_, _) => Rgba32.Black, image);
    }

    [Fact]
    public void Load_LocalColourTable_OverridesTheGlobalOne()
    {
        var local = new[] { new Rgba32(1, 2, 3), new Rgba32(4, 5, 6) };
        var file = new TestGif { ScreenWidth = 2, ScreenHeight = 1, FrameWidth = 2, FrameHeight = 1, Indices = [1, 0], GlobalPalette = [Rgba32.Black, Rgba32.White], LocalPalette = local }.ToBytes();

        var image = ImageAssert.Load(file);

        Assert.Equal(local[1], image.GetPixel(0, 0));
        Assert.Equal(local[0], image.GetPixel(1, 0));
    }

    [Fact]
    public void Load_TransparentIndex_IsTransparentAndNeverBurns()
    {
        var file = new TestGif { ScreenWidth = 3, ScreenHeight = 1, FrameWidth = 3, FrameHeight = 1, Indices = [0, 1, 0], GlobalPalette = [Rgba32.Black, Rgba32.White], TransparentIndex = 0 }.ToBytes();

        var image = ImageAssert.Load(file);
        var inverted = MaskBuilder.Build(image, new MaskOptions { Invert = true });

        Assert.Equal(0, image.GetPixel(0, 0).A);
        Assert.True(image.Info.HasAlpha);
        Assert.Equal(0, MaskBuilder.Build(image, MaskOptions.Default).CountSet());
        Assert.Equal((false, true, false), (inverted[0, 0], inverted[1, 0], inverted[2, 0]));
    }

    [Fact]
    public void Load_Interlaced_PutsRowsBackInOrder()
    {
        const int width = 5, height = 19;
        var indices = Enumerable.Range(0, width * height).Select(i => (byte)(i / width % 4)).ToArray();
        var palette = Palette(4, 9);
        var file = new TestGif { ScreenWidth = width, ScreenHeight = height, FrameWidth = width, FrameHeight = height, Indices = indices, GlobalPalette = palette, Interlaced = true }.ToBytes();

        var image = ImageAssert.Load(file);

        ImageAssert.PixelsEqual((x, y) => palette[indices[(y * width) + x]], image);
        Assert.True(image.Info.Interlaced);
    }

    [Theory]
    [InlineData(4)]
    [InlineData(256)]
    public void Load_FrameSmallerThanScreen_LeavesTheRestTransparent(int colours)
    {
        var palette = Palette(colours, 3);
        var file = new TestGif { ScreenWidth = 6, ScreenHeight = 4, Left = 2, Top = 1, FrameWidth = 3, FrameHeight = 2, Indices = [1, 2, 3, 3, 2, 1], GlobalPalette = palette }.ToBytes();

        var image = ImageAssert.Load(file);

        Assert.Equal((6, 4), (image.Width, image.Height));
        ImageAssert.PixelsEqual(
            (x, y) => x is >= 2 and < 5 && y is >= 1 and < 3 ? palette[new[] { 1, 2, 3, 3, 2, 1 }[((y - 1) * 3) + x - 2]] : Rgba32.Transparent,
            image);
    }

    [Fact]
    public void Load_TruncatedImageData_IsRefused()
    {
        var indices = Enumerable.Range(0, 400).Select(i => (byte)(i * 7 % 16)).ToArray();
        var file = new TestGif { ScreenWidth = 20, ScreenHeight = 20, FrameWidth = 20, FrameHeight = 20, Indices = indices, GlobalPalette = Palette(16, 1) }.ToBytes();

        var ex = ImageAssert.Refused(file[..(file.Length - 40)]);

        Assert.Contains("truncated", ex.Problem, StringComparison.Ordinal);
    }

    [Fact]
    public void Load_NoColourTable_IsRefused()
    {
        var file = new TestGif { ScreenWidth = 1, ScreenHeight = 1, FrameWidth = 1, FrameHeight = 1, Indices = [0], GlobalPalette = [Rgba32.Black, Rgba32.White] }.ToBytes();
        file[10] &= 0x7F;
        var withoutTable = file[..13].Concat(file[19..]).ToArray();

        Assert.Contains("colour table", ImageAssert.Refused(withoutTable).Problem, StringComparison.Ordinal);
    }

    [Fact]
    public void Load_HugeFrameWithLittleData_IsRefusedBeforeAllocating()
    {
        var file = new TestGif { ScreenWidth = 60000, ScreenHeight = 60000, FrameWidth = 60000, FrameHeight = 60000, Indices = [0, 1, 0], GlobalPalette = [Rgba32.Black, Rgba32.White] }.ToBytes();
        var before = GC.GetAllocatedBytesForCurrentThread();

        var ex = ImageAssert.Refused(file);

        Assert.True(GC.GetAllocatedBytesForCurrentThread() - before < 1 << 20);
        Assert.Contains("60000", ex.Problem, StringComparison.Ordinal);
    }

    [Fact]
    public void FrameRow_Interlaced_VisitsEveryRowOnce()
    {
        for (var height = 1; height <= 40; height++)
        {
            var rows = Enumerable.Range(0, height).Select(i => GifDecoder.FrameRow(i, height, interlaced: true)).Order();

            Assert.Equal(Enumerable.Range(0, height), rows);
        }
    }
}
