using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Tests.Imaging;

/// <summary>The images in assets/ that a user starts with load, and the QR code is the right way up.</summary>
public class StarterAssetsTests
{
    internal static string Asset(string name)
    {
        var folder = new DirectoryInfo(AppContext.BaseDirectory);
        while (folder is not null && !File.Exists(Path.Combine(folder.FullName, "LaserEngrave.sln")))
        {
            folder = folder.Parent;
        }

        Assert.NotNull(folder);
        return Path.Combine(folder.FullName, "assets", name);
    }

    [Theory]
    [InlineData("qr-code.bmp", ImageFormat.Bmp)]
    [InlineData("text-banner.png", ImageFormat.Png)]
    [InlineData("line-drawing.png", ImageFormat.Png)]
    public void Asset_Loads_AsOneBitImageWithSomethingToBurn(string name, ImageFormat format)
    {
        var mask = MaskBuilder.FromFile(Asset(name), MaskOptions.Default, out var info);

        Assert.Equal(format, info.Format);
        Assert.Equal(1, info.BitsPerPixel);
        Assert.InRange(mask.CountSet(), 1, mask.Width * (long)mask.Height / 2);
        Assert.InRange(info.Width, 29, 400);
    }

    [Fact]
    public void GreySample_Dithered_BurnsEachWedgeStepInProportionToItsGrey()
    {
        // The grey sample (tools/make-grey-sample.py) is for trying dithers: greys the threshold alone makes black or white.
        var path = Asset("grey-sample.png");
        var thresholded = MaskBuilder.FromFile(path, MaskOptions.Default, out var info);
        var dithered = MaskBuilder.FromFile(path, MaskOptions.Default with { Dither = DitherMethod.FloydSteinberg }, out _);

        Assert.Equal(ImageFormat.Png, info.Format);
        Assert.Equal(8, info.BitsPerPixel);
        Assert.Equal((320, 240), (info.Width, info.Height));
        var previous = 1.1;
        for (var step = 0; step <= 10; step++)
        {
            // The wedge's step of step * 10 % grey, rows 210..229 away from its edges: the dots burned follow the grey.
            var left = (step * 320 / 11) + 4;
            var right = ((step + 1) * 320 / 11) - 4;
            var set = 0;
            for (var y = 210; y < 230; y++)
            {
                for (var x = left; x < right; x++)
                {
                    set += dithered[x, y] ? 1 : 0;
                }
            }

            var fraction = set / (double)((right - left) * 20);
            Assert.InRange(fraction, 1 - (step / 10.0) - 0.08, 1 - (step / 10.0) + 0.08);
            Assert.True(fraction <= previous, $"step {step}: {fraction} after {previous}");
            previous = fraction;
        }

        Assert.NotEqual(thresholded.CountSet(), dithered.CountSet());
    }

    [Fact]
    public void QrCode_HasFinderPatternsAtTopLeftTopRightAndBottomLeftOnly()
    {
        var mask = MaskBuilder.FromFile(Asset("qr-code.bmp"), MaskOptions.Default, out var info);
        const int quiet = 4;
        var modules = info.Width - (2 * quiet);

        Assert.Equal(info.Width, info.Height);
        Assert.True(modules is >= 21 and <= 41 && (modules - 17) % 4 == 0, $"{modules} modules is not a QR version size");
        Assert.True(IsFinder(mask, quiet, quiet));
        Assert.True(IsFinder(mask, quiet + modules - 7, quiet));
        Assert.True(IsFinder(mask, quiet, quiet + modules - 7));
        Assert.False(IsFinder(mask, quiet + modules - 7, quiet + modules - 7));
        for (var i = 0; i < info.Width; i++)
        {
            Assert.False(mask[i, 0] || mask[0, i] || mask[i, info.Height - 1] || mask[info.Width - 1, i], "the quiet zone must stay unburnt");
        }
    }

    /// <summary>A 7 x 7 finder: dark ring, light ring, dark 3 x 3 centre.</summary>
    private static bool IsFinder(BitMask mask, int left, int top)
    {
        for (var y = 0; y < 7; y++)
        {
            for (var x = 0; x < 7; x++)
            {
                var ring = Math.Max(Math.Abs(x - 3), Math.Abs(y - 3));
                if (mask[left + x, top + y] != (ring != 2))
                {
                    return false;
                }
            }
        }

        return true;
    }
}
