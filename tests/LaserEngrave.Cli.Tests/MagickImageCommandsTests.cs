using System.Text.Json;
using ImageMagick;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Cli.Tests;

/// <summary>`info` and `mask` on JPEG and TIFF files, which Core decodes through ImageMagick.</summary>
public class MagickImageCommandsTests
{
    [Fact]
    public async Task Info_Jpeg_PrintsFormatSizeAndResolution()
    {
        var path = Write(MagickFormat.Jpeg, ".jpg");
        try
        {
            var (exit, output, error) = await CliHarness.RunAsync("info", path);

            Assert.Equal(0, exit);
            Assert.Empty(error);
            Assert.Contains("Format:          JPEG", output, StringComparison.Ordinal);
            Assert.Contains("64 x 32 px", output, StringComparison.Ordinal);
            Assert.Contains("Resolution:      600 x 600 dpi", output, StringComparison.Ordinal);
            Assert.Contains("Compression:     JPEG", output, StringComparison.Ordinal);
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public async Task InfoJson_Jpeg_IsOneObjectWithFormatAndDpi()
    {
        var path = Write(MagickFormat.Jpeg, ".jpg");
        try
        {
            var (exit, output, _) = await CliHarness.RunAsync("info", path, "--json");

            Assert.Equal(0, exit);
            using var json = JsonDocument.Parse(output);
            Assert.Equal("jpeg", json.RootElement.GetProperty("format").GetString());
            Assert.Equal(600, json.RootElement.GetProperty("dpiX").GetDouble());
            Assert.Equal(1, json.RootElement.GetProperty("frameCount").GetInt32());
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public async Task Mask_Jpeg_WritesTheRectangleBlackOnWhite()
    {
        var path = Write(MagickFormat.Jpeg, ".jpg");
        var maskPath = CliHarness.TempFile(".png");
        try
        {
            var (exit, output, error) = await CliHarness.RunAsync("mask", path, "--out", maskPath);

            Assert.Equal(0, exit);
            Assert.Empty(error);
            Assert.Contains("64 x 32 px, 512 to burn (25.0 %)", output, StringComparison.Ordinal);
            var mask = MaskBuilder.FromFile(maskPath, MaskOptions.Default, out _);
            for (var y = 0; y < mask.Height; y++)
            {
                for (var x = 0; x < mask.Width; x++)
                {
                    Assert.True(mask[x, y] == InRectangle(x, y), $"mask pixel ({x}, {y})");
                }
            }
        }
        finally
        {
            File.Delete(path);
            File.Delete(maskPath);
        }
    }

    [Fact]
    public async Task Mask_MultiPageTiff_WarnsThatOnlyTheFirstPageIsUsed()
    {
        var path = CliHarness.TempFile(".tif");
        var maskPath = CliHarness.TempFile(".png");
        using (var pages = new MagickImageCollection())
        {
            pages.Add(new MagickImage(MagickColors.Black, 8, 8));
            pages.Add(new MagickImage(MagickColors.White, 8, 8));
            await pages.WriteAsync(path, MagickFormat.Tiff, TestContext.Current.CancellationToken);
        }

        try
        {
            var (exit, output, error) = await CliHarness.RunAsync("mask", path, "--out", maskPath);

            Assert.Equal(0, exit);
            Assert.Contains("64 to burn", output, StringComparison.Ordinal);
            Assert.Equal($"warning: {path} holds 2 pages or frames; only the first is used", error.TrimEnd());
        }
        finally
        {
            File.Delete(path);
            File.Delete(maskPath);
        }
    }

    [Fact]
    public async Task Mask_TruncatedJpeg_OneLineExit2NamingTheFile()
    {
        var path = CliHarness.TempFile(".jpg");
        var whole = Encode(MagickFormat.Jpeg);
        await File.WriteAllBytesAsync(path, whole[..(whole.Length / 2)], TestContext.Current.CancellationToken);
        try
        {
            var (exit, output, error) = await CliHarness.RunAsync("mask", path, "--out", CliHarness.TempFile(".png"));

            Assert.Equal(2, exit);
            Assert.Empty(output);
            Assert.Single(error.TrimEnd().Split('\n'));
            Assert.StartsWith($"laserengrave: {path}: the JPEG data is corrupt or truncated", error, StringComparison.Ordinal);
        }
        finally
        {
            File.Delete(path);
        }
    }

    private static bool InRectangle(int x, int y) => x is >= 16 and < 48 && y is >= 8 and < 24;

    /// <summary>A 64 x 32 white image with a black 32 x 16 rectangle, at 600 dpi.</summary>
    private static byte[] Encode(MagickFormat format)
    {
        using var image = new MagickImage(MagickColors.White, 64, 32);
        using (var pixels = image.GetPixels())
        {
            pixels.SetArea(16, 8, 32, 16, new byte[32 * 16 * 3]);
        }

        image.Density = new Density(600, 600, DensityUnit.PixelsPerInch);
        return image.ToByteArray(format);
    }

    private static string Write(MagickFormat format, string extension)
    {
        var path = CliHarness.TempFile(extension);
        File.WriteAllBytes(path, Encode(format));
        return path;
    }
}
