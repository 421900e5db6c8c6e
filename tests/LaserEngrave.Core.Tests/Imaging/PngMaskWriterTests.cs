using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Tests.Imaging;

/// <summary>Masks are written as 1-bit PNGs, a row at a time, and read back the same.</summary>
public sealed class PngMaskWriterTests
{
    [Theory]
    [InlineData(1, 1)]
    [InlineData(7, 3)]
    [InlineData(9, 2)]
    [InlineData(65, 4)]
    [InlineData(130, 5)]
    public void WriteMask_AnyWidth_ReadsBackTheSameMask(int width, int height)
    {
        var mask = new BitMask(width, height);
        var random = new Random(width * 31 + height);
        for (var y = 0; y < height; y++)
        {
            for (var x = 0; x < width; x++)
            {
                mask[x, y] = random.Next(2) == 1;
            }
        }

        using var png = new MemoryStream();
        PngWriter.WriteMask(png, mask);
        png.Position = 0;
        var back = MaskBuilder.Build(ImageLoader.Load(png, "mask.png"), MaskOptions.Default);

        Assert.True(mask.ContentEquals(back));
        Assert.Equal(1, png.GetBuffer()[24]);
    }

    [Fact]
    public void WriteMask_LargeMask_SeveralIdatChunksNoOverflow()
    {
        // 40000 x 2000: 80 Mpx, a 10 MB mask; the old writer made an 80 MB grey copy and one IDAT chunk.
        var mask = new BitMask(40_000, 2_000);
        for (var y = 0; y < mask.Height; y += 3)
        {
            mask[(y * 7919) % mask.Width, y] = true;
        }

        using var png = new MemoryStream();
        PngWriter.WriteMask(png, mask);
        png.Position = 0;
        var back = MaskBuilder.Build(ImageLoader.Load(png, "mask.png"), MaskOptions.Default);

        Assert.True(mask.ContentEquals(back));
    }

    [Fact]
    public void WriteMask_FolderMissing_ThrowsAndLeavesNoFile()
    {
        var folder = Path.Combine(Path.GetTempPath(), $"le-png-{Guid.NewGuid():N}");
        var path = Path.Combine(folder, "o.png");

        Assert.ThrowsAny<IOException>(() => PngWriter.WriteMask(path, new BitMask(2, 2)));

        Assert.False(File.Exists(path));
    }

    [Fact]
    public void WriteMask_ToAFile_NoTemporaryLeftBeside()
    {
        var folder = Directory.CreateTempSubdirectory("le-png-").FullName;
        try
        {
            PngWriter.WriteMask(Path.Combine(folder, "o.png"), new BitMask(3, 3));

            Assert.Equal(["o.png"], Directory.GetFiles(folder).Select(Path.GetFileName));
        }
        finally
        {
            Directory.Delete(folder, recursive: true);
        }
    }
}
