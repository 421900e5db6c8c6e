using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Tests.Imaging;

public class MaskBuilderTests
{
    private static readonly DitherMethod[] Dithers = [DitherMethod.FloydSteinberg, DitherMethod.Atkinson, DitherMethod.Bayer];

    /// <summary>A full-colour PNG of one colour per pixel, built through the public decoder.</summary>
    private static LoadedImage Rgba(int width, int height, Func<int, int, Rgba32> colour)
    {
        var samples = new int[width * height * 4];
        for (var y = 0; y < height; y++)
        {
            for (var x = 0; x < width; x++)
            {
                var c = colour(x, y);
                new[] { c.R, c.G, c.B, c.A }.Select(v => (int)v).ToArray().CopyTo(samples, ((y * width) + x) * 4);
            }
        }

        return ImageAssert.Load(new TestPng { Width = width, Height = height, ColourType = 6, Samples = samples }.ToBytes());
    }

    private static LoadedImage Grey(int width, int height, byte level) => Rgba(width, height, (_, _) => new Rgba32(level, level, level));

    [Theory]
    [InlineData(false)]
    [InlineData(true)]
    public void Build_OneBitPalette_BurnsTheBlackWhicheverIndexItHas(bool whiteFirst)
    {
        var indices = new[,] { { 0, 1, 1, 0, 1 } };
        var palette = whiteFirst ? new[] { Rgba32.White, Rgba32.Black } : [Rgba32.Black, Rgba32.White];
        var bytes = new TestBmp { Width = 5, Height = 1, Palette = palette, Rows = TestBmp.PackIndices(indices, 1) }.ToBytes();
        using var file = ImageAssert.Write(bytes, ".bmp");

        var built = MaskBuilder.Build(ImageLoader.Load(file.Path), MaskOptions.Default);
        var direct = MaskBuilder.FromFile(file.Path, MaskOptions.Default, out var info);

        var blackIndex = whiteFirst ? 1 : 0;
        ImageAssert.MaskEquals((x, _) => indices[0, x] == blackIndex, built);
        ImageAssert.MaskEquals((x, _) => indices[0, x] == blackIndex, direct);
        Assert.Equal(5, info.Width);
    }

    [Theory]
    [InlineData(50, 128)]
    [InlineData(0, 0)]
    [InlineData(100, 255)]
    [InlineData(25, 64)]
    public void Build_Threshold_BurnsGreysDarkerThanIt(double percent, int burnt)
    {
        // Grey levels 0..255 in one row; luminance v / 255 burns when below percent / 100.
        var image = Rgba(256, 1, (x, _) => new Rgba32((byte)x, (byte)x, (byte)x));

        var mask = MaskBuilder.Build(image, new MaskOptions { ThresholdPercent = percent });

        Assert.Equal(burnt, mask.CountSet());
        ImageAssert.MaskEquals((x, _) => x < burnt, mask);
    }

    [Fact]
    public void Build_ColourLuminance_UsesRec709Weights()
    {
        // Pure green (luma 0.7152) is light and pure blue (0.0722) dark, unlike an average of channels.
        var image = Rgba(3, 1, (x, _) => x switch { 0 => new Rgba32(255, 0, 0), 1 => new Rgba32(0, 255, 0), _ => new Rgba32(0, 0, 255) });

        var mask = MaskBuilder.Build(image, MaskOptions.Default);

        Assert.Equal((true, false, true), (mask[0, 0], mask[1, 0], mask[2, 0]));
        Assert.Equal(0.2126, new Rgba32(255, 0, 0).Luminance, 10);
    }

    [Fact]
    public void Build_Invert_ComplementsOpaquePixelsOnly()
    {
        var image = Rgba(70, 3, (x, y) => y == 2 && x % 3 == 0 ? Rgba32.Transparent : new Rgba32((byte)(x * 3), 0, (byte)(y * 90)));

        var normal = MaskBuilder.Build(image, MaskOptions.Default);
        var inverted = MaskBuilder.Build(image, new MaskOptions { Invert = true });

        ImageAssert.MaskEquals((x, y) => image.GetPixel(x, y).A != 0 && !normal[x, y], inverted);
    }

    [Fact]
    public void Build_FullyTransparentPixels_NeverBurnWithAnyOption()
    {
        var image = Rgba(16, 16, (x, y) => (x + y) % 2 == 0 ? new Rgba32(0, 0, 0, 0) : Rgba32.Black);

        foreach (var dither in Dithers.Append(DitherMethod.None))
        {
            foreach (var invert in new[] { false, true })
            {
                var mask = MaskBuilder.Build(image, new MaskOptions { Dither = dither, Invert = invert, ThresholdPercent = 100 });

                for (var y = 0; y < 16; y++)
                {
                    for (var x = 0; x < 16; x++)
                    {
                        Assert.False((x + y) % 2 == 0 && mask[x, y], $"transparent ({x}, {y}) burnt with {dither}, invert {invert}");
                    }
                }
            }
        }
    }

    [Fact]
    public void Build_HalfTransparentBlack_IsCompositedOverWhite()
    {
        var image = Rgba(2, 1, (x, _) => new Rgba32(0, 0, 0, x == 0 ? (byte)100 : (byte)160));

        var mask = MaskBuilder.Build(image, MaskOptions.Default);

        // Over white, alpha 100/255 gives 61 % luminance (no burn), 160/255 gives 37 % (burn).
        Assert.Equal((false, true), (mask[0, 0], mask[1, 0]));
    }

    [Theory]
    [InlineData(DitherMethod.FloydSteinberg)]
    [InlineData(DitherMethod.Atkinson)]
    [InlineData(DitherMethod.Bayer)]
    public void Build_DitheredMidGrey_BurnsAboutHalf(DitherMethod dither)
    {
        var mask = MaskBuilder.Build(Grey(64, 64, 128), new MaskOptions { Dither = dither });

        var fraction = mask.CountSet() / (64.0 * 64);
        Assert.InRange(fraction, 0.46, 0.54);
        Assert.InRange(mask.CountSet(0), 20, 44);
    }

    [Theory]
    [InlineData(DitherMethod.FloydSteinberg)]
    [InlineData(DitherMethod.Bayer)]
    public void Build_DitheredGreyLevels_BurnInProportionToDarkness(DitherMethod dither)
    {
        foreach (var level in new byte[] { 0, 32, 64, 96, 160, 192, 224, 255 })
        {
            var mask = MaskBuilder.Build(Grey(64, 64, level), new MaskOptions { Dither = dither });

            var expected = 1 - (level / 255.0);
            Assert.InRange(mask.CountSet() / (64.0 * 64), expected - 0.06, expected + 0.06);
        }
    }

    [Fact]
    public void Build_AtkinsonGreyLevels_BurnLessAsTheyLightenAndClipTheExtremes()
    {
        // Atkinson passes on only 6/8 of the error, so near-black turns black and near-white white, keeping contrast.
        var fractions = new[] { 0, 32, 96, 128, 160, 224, 255 }
            .Select(level => MaskBuilder.Build(Grey(64, 64, (byte)level), new MaskOptions { Dither = DitherMethod.Atkinson }).CountSet() / (64.0 * 64))
            .ToArray();

        Assert.Equal(fractions.OrderDescending(), fractions);
        Assert.Equal(1.0, fractions[0]);
        Assert.Equal(0.0, fractions[^1]);
        Assert.InRange(fractions[1], 1 - (32 / 255.0), 1.0);
        Assert.InRange(fractions[5], 0.0, 1 - (224 / 255.0));
        Assert.InRange(fractions[3], 0.4, 0.6);
    }

    [Fact]
    public void Build_Bayer_IsExactHalfAndRepeatsEveryEightPixels()
    {
        var image = Grey(40, 24, 128);
        var options = new MaskOptions { Dither = DitherMethod.Bayer };

        var mask = MaskBuilder.Build(image, options);
        var again = MaskBuilder.Build(image, options);

        Assert.True(mask.ContentEquals(again));
        Assert.Equal(40 * 24 / 2, mask.CountSet());
        for (var y = 0; y < 16; y++)
        {
            for (var x = 0; x < 32; x++)
            {
                Assert.Equal(mask[x, y], mask[x + 8, y + 8]);
            }
        }
    }

    [Fact]
    public void BayerIndex_IsTheClassicMatrix()
    {
        // The first two rows of the standard 8 x 8 Bayer matrix, and every level used once.
        Assert.Equal([0, 32, 8, 40, 2, 34, 10, 42], Enumerable.Range(0, 8).Select(x => BayerDitherer.Index(x, 0)));
        Assert.Equal([48, 16, 56, 24, 50, 18, 58, 26], Enumerable.Range(0, 8).Select(x => BayerDitherer.Index(x, 1)));
        Assert.Equal(Enumerable.Range(0, 64), Enumerable.Range(0, 64).Select(i => BayerDitherer.Index(i % 8, i / 8)).Order());
    }

    [Theory]
    [InlineData(DitherMethod.FloydSteinberg)]
    [InlineData(DitherMethod.Atkinson)]
    [InlineData(DitherMethod.Bayer)]
    public void Build_DitherOfBlackAndWhitePalette_EqualsThreshold(DitherMethod dither)
    {
        var random = new Random(5);
        var indices = new int[9, 77];
        for (var y = 0; y < 9; y++)
        {
            for (var x = 0; x < 77; x++)
            {
                indices[y, x] = random.Next(2);
            }
        }

        var image = ImageAssert.Load(new TestBmp { Width = 77, Height = 9, Rows = TestBmp.PackIndices(indices, 1) }.ToBytes());

        Assert.True(MaskBuilder.Build(image, new MaskOptions { Dither = dither }).ContentEquals(MaskBuilder.Build(image, MaskOptions.Default)));
    }

    [Fact]
    public void Build_DitheredGreyPalette_UsesThePaletteColours()
    {
        var palette = new[] { new Rgba32(128, 128, 128), Rgba32.Black };
        var rows = Enumerable.Range(0, 32).Select(_ => new byte[4]).ToArray();
        var image = ImageAssert.Load(new TestBmp { Width = 32, Height = 32, Palette = palette, Rows = rows }.ToBytes());

        var mask = MaskBuilder.Build(image, new MaskOptions { Dither = DitherMethod.Bayer });

        Assert.Equal(32 * 32 / 2, mask.CountSet());
    }

    [Theory]
    [InlineData(1)]
    [InlineData(2)]
    [InlineData(4)]
    [InlineData(8)]
    public void Build_PalettePathOnRandomImages_MatchesPerPixelRule(int bits)
    {
        // The word-wise palette path against the rule applied pixel by pixel, over many widths and palettes.
        var random = new Random(bits);
        for (var trial = 0; trial < 40; trial++)
        {
            var width = random.Next(1, 200);
            var height = random.Next(1, 5);
            var palette = Enumerable.Range(0, 1 << bits).Select(_ => new Rgba32((byte)random.Next(256), (byte)random.Next(256), (byte)random.Next(256))).ToArray();
            var indices = new int[height, width];
            for (var y = 0; y < height; y++)
            {
                for (var x = 0; x < width; x++)
                {
                    indices[y, x] = random.Next(palette.Length);
                }
            }

            var options = new MaskOptions { ThresholdPercent = random.Next(101), Invert = random.Next(2) == 1 };
            var bytes = new TestBmp { Width = width, Height = height, BitsPerPixel = bits, Palette = palette, Rows = TestBmp.PackIndices(indices, bits) }.ToBytes();
            using var file = ImageAssert.Write(bytes, ".bmp");

            bool Expected(int x, int y) => (palette[indices[y, x]].Luminance < options.ThresholdPercent / 100) ^ options.Invert;
            ImageAssert.MaskEquals(Expected, MaskBuilder.Build(ImageLoader.Load(file.Path), options));
            ImageAssert.MaskEquals(Expected, MaskBuilder.FromFile(file.Path, options, out _));
        }
    }

    [Fact]
    public void ReverseBitsInEachByte_MatchesBitByBitReversal()
    {
        var random = new Random(1);
        for (var i = 0; i < 1000; i++)
        {
            var value = (ulong)random.NextInt64() ^ ((ulong)random.Next() << 40);
            ulong expected = 0;
            for (var bit = 0; bit < 64; bit++)
            {
                var byteIndex = bit / 8;
                var inByte = bit % 8;
                expected |= ((value >> bit) & 1) << ((byteIndex * 8) + (7 - inByte));
            }

            Assert.Equal(expected, PaletteMaskWriter.ReverseBitsInEachByte(value));
        }
    }

    [Theory]
    [InlineData(-1)]
    [InlineData(100.5)]
    [InlineData(double.NaN)]
    public void Build_ThresholdOutside0To100_IsRejected(double percent)
    {
        var image = Grey(1, 1, 0);

        Assert.Throws<ArgumentOutOfRangeException>(() => MaskBuilder.Build(image, new MaskOptions { ThresholdPercent = percent }));
    }

    [Fact]
    public void FromFile_NonBmp_DecodesAndBuilds()
    {
        var bytes = new TestPng { Width = 3, Height = 1, Samples = [0, 200, 10] }.ToBytes();
        using var file = ImageAssert.Write(bytes, ".png");

        var mask = MaskBuilder.FromFile(file.Path, MaskOptions.Default, out var info);

        Assert.Equal(ImageFormat.Png, info.Format);
        Assert.Equal((true, false, true), (mask[0, 0], mask[1, 0], mask[2, 0]));
    }

    [Fact]
    public void FromFile_BadFile_ThrowsImageLoadException()
    {
        using var file = ImageAssert.Write([.. "BM"u8, 1, 2], ".bmp");

        var ex = Assert.Throws<ImageLoadException>(() => MaskBuilder.FromFile(file.Path, MaskOptions.Default, out _));

        Assert.StartsWith(file.Path + ": ", ex.Message, StringComparison.Ordinal);
    }
}
