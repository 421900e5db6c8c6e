using System.Text.Json;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Cli.Tests;

public class ImageCommandsTests
{
    [Fact]
    public async Task Info_OneBitBmp_PrintsHeaderFacts()
    {
        var (exit, output, _) = await CliHarness.RunAsync("info", CliHarness.BmpSuite("g/pal1.bmp"));

        Assert.Equal(0, exit);
        Assert.Contains("127 x 64 px", output, StringComparison.Ordinal);
        Assert.Contains("Bits per pixel:  1", output, StringComparison.Ordinal);
        Assert.Contains("2 colours", output, StringComparison.Ordinal);
    }

    [Fact]
    public async Task InfoJson_PaletteBmp_IsOneObjectWithWidthAndHeight()
    {
        var (exit, output, _) = await CliHarness.RunAsync("info", CliHarness.BmpSuite("g/pal8.bmp"), "--json");

        Assert.Equal(0, exit);
        using var json = JsonDocument.Parse(output);
        Assert.Equal(127, json.RootElement.GetProperty("width").GetInt32());
        Assert.Equal(64, json.RootElement.GetProperty("height").GetInt32());
        // The suite's pal8.bmp declares 252 colours used (biClrUsed), not 256.
        Assert.Equal(252, json.RootElement.GetProperty("paletteSize").GetInt32());
    }

    [Fact]
    public async Task Info_NotAnImage_OneLineExit2NamingTheFile()
    {
        var path = CliHarness.TempFile(".bmp");
        await File.WriteAllTextAsync(path, "hello, not a bitmap", TestContext.Current.CancellationToken);
        try
        {
            var (exit, output, error) = await CliHarness.RunAsync("info", path);

            Assert.Equal(2, exit);
            Assert.Empty(output);
            Assert.Single(error.TrimEnd().Split('\n'));
            Assert.Contains(path, error, StringComparison.Ordinal);
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public async Task Info_BadBmpFromSuite_RefusedWithoutStackTrace()
    {
        var (exit, _, error) = await CliHarness.RunAsync("info", CliHarness.BmpSuite("b/reallybig.bmp"));
        var (maskExit, _, maskError) = await CliHarness.RunAsync("mask", CliHarness.BmpSuite("b/reallybig.bmp"), "--out", CliHarness.TempFile(".png"));

        Assert.Equal(2, maskExit);
        Assert.DoesNotContain("   at ", maskError, StringComparison.Ordinal);
        Assert.Contains("reallybig.bmp", maskError, StringComparison.Ordinal);
        Assert.True(exit is 0 or 2, error);
    }

    [Fact]
    public async Task Mask_InvertedOneBitBmp_WritesComplementMask()
    {
        var plain = CliHarness.TempFile(".png");
        var inverted = CliHarness.TempFile(".png");
        try
        {
            var source = CliHarness.BmpSuite("g/pal1.bmp");
            Assert.Equal(0, (await CliHarness.RunAsync("mask", source, "--out", plain)).Exit);
            Assert.Equal(0, (await CliHarness.RunAsync("mask", source, "--out", inverted, "--invert")).Exit);

            var a = MaskBuilder.FromFile(plain, MaskOptions.Default, out _);
            var b = MaskBuilder.FromFile(inverted, MaskOptions.Default, out _);
            Assert.Equal((long)a.Width * a.Height, a.CountSet() + b.CountSet());
            Assert.True(MaskBuilder.FromFile(source, MaskOptions.Default, out _).ContentEquals(a));
        }
        finally
        {
            File.Delete(plain);
            File.Delete(inverted);
        }
    }

    [Theory]
    [InlineData("--threshold", "120")]
    [InlineData("--dither", "sparkle")]
    public async Task Mask_BadOption_Exit2NamingTheValue(string option, string value)
    {
        var (exit, _, error) = await CliHarness.RunAsync("mask", CliHarness.BmpSuite("g/pal8.bmp"), "--out", CliHarness.TempFile(".png"), option, value);

        Assert.Equal(2, exit);
        Assert.Contains(value, error, StringComparison.Ordinal);
    }
}
