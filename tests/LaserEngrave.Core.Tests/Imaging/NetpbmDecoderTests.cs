using System.Text;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Tests.Imaging;

public class NetpbmDecoderTests
{
    private static byte[] Ascii(string text) => Encoding.ASCII.GetBytes(text);

    [Fact]
    public void Load_PlainAndRawBitmap_AgreeAndOneIsBlack()
    {
        var plain = ImageAssert.Load(Ascii("P1\n# a comment\n10 2\n1010000001\n0 1 0 1 0 1 0 1 0 1\n"));
        var raw = ImageAssert.Load([.. Ascii("P4 10 2\n"), 0b1010_0000, 0b0100_0000, 0b0101_0101, 0b0100_0000]);

        ImageAssert.PixelsEqual(plain.GetPixel, raw);
        Assert.Equal(Rgba32.Black, plain.GetPixel(0, 0));
        Assert.Equal(Rgba32.White, plain.GetPixel(1, 0));
        Assert.Equal(Rgba32.Black, plain.GetPixel(9, 0));
        Assert.Equal(ImageFormat.Pbm, raw.Info.Format);
        Assert.Equal(("ASCII", "none"), (plain.Info.Compression, raw.Info.Compression));
        Assert.Equal(3, MaskBuilder.Build(plain, MaskOptions.Default).CountSet(0));
    }

    [Fact]
    public void Load_Greymaps_ScaleToTheirMaxval()
    {
        var plain = ImageAssert.Load(Ascii("P2 3 1 4\n0 2 4\n"));
        var raw = ImageAssert.Load([.. Ascii("P5 3 1 4\n"), 0, 2, 4]);
        var wide = ImageAssert.Load([.. Ascii("P5 3 1 65535\n"), 0, 0, 0x80, 0x00, 0xFF, 0xFF]);

        Rgba32[] expected = [Rgba32.Black, new(128, 128, 128), Rgba32.White];
        ImageAssert.PixelsEqual((x, _) => expected[x], plain);
        ImageAssert.PixelsEqual((x, _) => expected[x], raw);
        ImageAssert.PixelsEqual((x, _) => expected[x], wide);
        Assert.Equal(16, wide.Info.BitsPerPixel);
    }

    [Fact]
    public void Load_Pixmaps_ReadRgb()
    {
        var plain = ImageAssert.Load(Ascii("P3\n2 1\n255\n255 0 0  0 0 255\n"));
        var raw = ImageAssert.Load([.. Ascii("P6 2 1 255\n"), 255, 0, 0, 0, 0, 255]);
        var wide = ImageAssert.Load([.. Ascii("P6 2 1 1000\n"), 0x03, 0xE8, 0, 0, 0, 0, 0, 0, 0, 0, 0x03, 0xE8]);

        Rgba32[] expected = [new(255, 0, 0), new(0, 0, 255)];
        ImageAssert.PixelsEqual((x, _) => expected[x], plain);
        ImageAssert.PixelsEqual((x, _) => expected[x], raw);
        ImageAssert.PixelsEqual((x, _) => expected[x], wide);
        Assert.Equal(ImageFormat.Ppm, raw.Info.Format);
    }

    [Theory]
    [InlineData("P5 100 100 255\n", "truncated")]
    [InlineData("P2 2 1 10\n3 11\n", "exceeds the maxval")]
    [InlineData("P2 2 1 70000\n3 1\n", "maxval 70000")]
    [InlineData("P1 2 1\n0 2\n", "must be 0 or 1")]
    [InlineData("P2 x 1 10\n", "width is not a number")]
    [InlineData("P3 0 5 255\n", "not positive")]
    [InlineData("P1 99999999999 1\n", "too large")]
    [InlineData("P7\nWIDTH 1\n", "PAM")]
    public void Load_BadNetpbm_IsRefused(string text, string problem)
    {
        var ex = ImageAssert.Refused(Ascii(text));

        Assert.Contains(problem, ex.Problem, StringComparison.Ordinal);
    }

    [Fact]
    public void Load_PlainFileTooShortForItsSize_IsRefusedBeforeAllocating()
    {
        var before = GC.GetAllocatedBytesForCurrentThread();

        var ex = ImageAssert.Refused(Ascii("P3 20000 20000 255\n1 2 3\n"));

        Assert.Contains("truncated", ex.Problem, StringComparison.Ordinal);
        Assert.True(GC.GetAllocatedBytesForCurrentThread() - before < 1 << 20);
    }
}
