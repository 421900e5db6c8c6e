using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Tests.Imaging;

public class ImageLoaderTests
{
    public static TheoryData<string, byte[]> UnsupportedSignatures => new()
    {
        { "QOI", [.. "qoif"u8, 0, 0, 0, 4, 0, 0, 0, 4, 3, 0] },
        { "Photoshop", [.. "8BPS"u8, 0, 1] },
        { "PDF", [.. "%PDF-1.7"u8] },
    };

    [Theory]
    [MemberData(nameof(UnsupportedSignatures))]
    public void Load_RecognisedFormatWithoutDecoder_SaysToSaveAsPngOrBmp(string format, byte[] head)
    {
        using var file = ImageAssert.Write([.. head, .. new byte[64]], ".img");

        var ex = Assert.Throws<ImageLoadException>(() => ImageLoader.Load(file.Path));
        var info = Assert.Throws<ImageLoadException>(() => ImageLoader.ReadInfo(file.Path));

        Assert.Equal($"{file.Path}: {format} image: no decoder for that format is available in this build; save it as PNG or BMP and load that", ex.Message);
        Assert.Equal(ex.Message, info.Message);
    }

    [Fact]
    public void Load_EmptyFile_SaysSo()
    {
        using var file = ImageAssert.Write([], ".bmp");

        var ex = Assert.Throws<ImageLoadException>(() => ImageLoader.Load(file.Path));

        Assert.Equal($"{file.Path}: the file is empty", ex.Message);
        Assert.Equal(file.Path, ex.Path);
    }

    [Fact]
    public void Load_UnknownContent_ShowsTheFirstBytes()
    {
        var ex = ImageAssert.Refused("hello, world"u8.ToArray(), "notes.bmp");

        Assert.Equal("notes.bmp: not a BMP, PNG, GIF, JPEG, TIFF, WebP or Netpbm image", ex.Message);
    }

    [Fact]
    public void Load_MissingFile_SaysFileNotFound()
    {
        var path = Path.Combine(Path.GetTempPath(), $"no-such-{Guid.NewGuid():N}.bmp");

        var ex = Assert.Throws<ImageLoadException>(() => ImageLoader.Load(path));

        Assert.Equal($"{path}: file not found", ex.Message);
    }

    [Fact]
    public void ReadInfo_ReadsHeadersOnly_SoATruncatedPixelAreaStillGivesInfo()
    {
        var file = new TestBmp { Width = 100, Height = 100, PixelData = new byte[10] }.ToBytes();

        var info = ImageAssert.Info(file);

        Assert.Equal((100, 100, 1, 2), (info.Width, info.Height, info.BitsPerPixel, info.PaletteSize));
        ImageAssert.Refused(file);
    }

    [Fact]
    public void Load_ForwardOnlyStream_IsCopiedAndDecoded()
    {
        var file = new TestPng { Width = 2, Height = 2, Samples = [0, 255, 255, 0] }.ToBytes();
        using var stream = new ForwardOnlyStream(file);

        var image = ImageLoader.Load(stream, "piped.png");

        Assert.Equal(Rgba32.Black, image.GetPixel(0, 0));
        Assert.Equal("piped.png", image.Info.Path);
    }

    [Fact]
    public void Load_FromDisk_ReportsTheFileSize()
    {
        var bytes = new TestBmp { Width = 3, Height = 3, Rows = [[0], [0], [0]] }.ToBytes();
        using var file = ImageAssert.Write(bytes, ".bmp");

        var image = ImageLoader.Load(file.Path);

        Assert.Equal(bytes.Length, image.Info.FileSizeBytes);
        Assert.Equal(file.Path, image.Info.Path);
    }

    public static TheoryData<string> SampleFiles => new() { "bmp1", "bmp8rle", "bmp24", "png-interlaced", "png-palette", "gif", "pgm", "ppm-plain" };

    /// <summary>Cuts and corrupts valid files many ways: every outcome must be a decoded image or an <see cref="ImageLoadException"/>.</summary>
    [Theory]
    [MemberData(nameof(SampleFiles))]
    public void Load_TruncatedOrCorruptedFile_NeverFailsWithAnythingElse(string kind)
    {
        var original = Sample(kind);
        var random = new Random(kind.GetHashCode(StringComparison.Ordinal) & 0xFFFF);
        var variants = new List<byte[]>();
        for (var length = 0; length < original.Length; length += Math.Max(1, original.Length / 60))
        {
            variants.Add(original[..length]);
        }

        for (var i = 0; i < 300; i++)
        {
            var corrupt = (byte[])original.Clone();
            for (var flips = random.Next(1, 4); flips > 0; flips--)
            {
                corrupt[random.Next(corrupt.Length)] = (byte)random.Next(256);
            }

            variants.Add(corrupt);
        }

        foreach (var variant in variants)
        {
            try
            {
                var image = ImageAssert.Load(variant);
                MaskBuilder.Build(image, new MaskOptions { Dither = DitherMethod.FloydSteinberg });
            }
            catch (ImageLoadException ex)
            {
                Assert.DoesNotContain('\n', ex.Message);
            }
        }
    }

    private static byte[] Sample(string kind)
    {
        var random = new Random(42);
        int[] Samples(int count, int levels) => Enumerable.Range(0, count).Select(_ => random.Next(levels)).ToArray();
        var grey = Enumerable.Range(0, 16).Select(i => new Rgba32((byte)(i * 17), (byte)(i * 17), (byte)(i * 17))).ToArray();
        return kind switch
        {
            "bmp1" => new TestBmp { Width = 20, Height = 9, Rows = Enumerable.Range(0, 9).Select(_ => new byte[] { 0xA5, 0x3C, 0xF0 }).ToArray() }.ToBytes(),
            "bmp8rle" => new TestBmp
            {
                Width = 8,
                Height = 3,
                BitsPerPixel = 8,
                Compression = 1,
                Palette = grey,
                PixelData = [0x04, 0x01, 0x00, 0x04, 0x02, 0x03, 0x04, 0x05, 0x00, 0x00, 0x08, 0x07, 0x00, 0x00, 0x00, 0x02, 0x02, 0x00, 0x03, 0x09, 0x00, 0x01],
            }.ToBytes(),
            "bmp24" => new TestBmp { Width = 5, Height = 4, BitsPerPixel = 24, PixelData = Samples(64, 256).Select(v => (byte)v).ToArray() }.ToBytes(),
            "png-interlaced" => new TestPng { Width = 11, Height = 9, ColourType = 6, Samples = Samples(11 * 9 * 4, 256), Interlaced = true }.ToBytes(),
            "png-palette" => new TestPng { Width = 17, Height = 5, ColourType = 3, BitDepth = 2, Samples = Samples(85, 4), Palette = new byte[12], Transparency = [0] }.ToBytes(),
            "gif" => new TestGif { ScreenWidth = 30, ScreenHeight = 20, FrameWidth = 30, FrameHeight = 20, Indices = Samples(600, 16).Select(v => (byte)v).ToArray(), GlobalPalette = grey, TransparentIndex = 3 }.ToBytes(),
            "pgm" => [.. "P5 7 5 255\n"u8, .. Samples(35, 256).Select(v => (byte)v)],
            _ => System.Text.Encoding.ASCII.GetBytes("P3 3 2 15\n1 2 3 4 5 6 7 8 9\n10 11 12 13 14 15 0 1 2\n"),
        };
    }

    private sealed class ForwardOnlyStream(byte[] data) : MemoryStream(data)
    {
        public override bool CanSeek => false;
    }
}
