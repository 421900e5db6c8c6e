using ImageMagick;
using LaserEngrave.Core.Imaging;
using DitherMethod = LaserEngrave.Core.Imaging.DitherMethod;

namespace LaserEngrave.Core.Tests.Imaging;

/// <summary>JPEG, TIFF and WebP through ImageMagick: masks, metadata, and bad files refused with one line.</summary>
public class MagickDecoderTests
{
    public static TheoryData<string> Formats => new() { "jpeg", "tiff", "webp-lossy", "webp-lossless" };

    [Theory]
    [MemberData(nameof(Formats))]
    public void Load_BlackRectangleOnWhite_MaskIsExactlyTheRectangle(string kind)
    {
        var image = ImageAssert.Load(BlackOnWhite(kind));

        var mask = MaskBuilder.Build(image, MaskOptions.Default);

        Assert.Equal((TestMagick.Width, TestMagick.Height), (mask.Width, mask.Height));
        ImageAssert.MaskEquals(TestMagick.InRectangle, mask);
    }

    [Fact]
    public void Load_LowQualityJpeg_CompressionNoiseFlipsNoPixel()
    {
        var file = TestMagick.BlackOnWhite(MagickFormat.Jpeg, image => image.Quality = 20);
        var image = ImageAssert.Load(file);

        // The noise is there (values between black and white around the edges) but stays far from the 50 % threshold.
        var grey = 0;
        for (var y = 0; y < image.Height; y++)
        {
            for (var x = 0; x < image.Width; x++)
            {
                grey += image.GetPixel(x, y).Luminance is > 0.0 and < 1.0 ? 1 : 0;
            }
        }

        Assert.True(grey > 0, "the JPEG has no compression noise, so the test proves nothing");
        ImageAssert.MaskEquals(TestMagick.InRectangle, MaskBuilder.Build(image, MaskOptions.Default));
        ImageAssert.MaskEquals((x, y) => !TestMagick.InRectangle(x, y), MaskBuilder.Build(image, new MaskOptions { Invert = true }));
    }

    [Fact]
    public void Load_GreyJpeg_IsEightBitIndicesIntoAGreyRamp()
    {
        var file = TestMagick.Grey((x, _) => (byte)(x * 4), MagickFormat.Jpeg, image => image.ColorType = ColorType.Grayscale);

        var image = ImageAssert.Load(file);

        Assert.Equal(PixelLayout.Indexed, image.Layout);
        Assert.Equal(8, image.BitsPerIndex);
        Assert.Equal(256, image.Palette.Length);
        Assert.Equal(8, image.Info.BitsPerPixel);
        Assert.Equal(0, image.Info.PaletteSize);
        Assert.InRange(image.GetPixel(63, 5).R, 240, 255);
    }

    [Fact]
    public void Load_ThresholdPercent_MovesTheEdgeOfAGreyRamp()
    {
        // A lossless ramp: grey level 4x in column x; 25 % of white is 63.75, so columns 0..15 are darker.
        var file = TestMagick.Grey((x, _) => (byte)(x * 4), MagickFormat.Tiff);

        var mask = MaskBuilder.Build(ImageAssert.Load(file), new MaskOptions { ThresholdPercent = 25 });

        ImageAssert.MaskEquals((x, _) => x < 16, mask);
    }

    [Fact]
    public void Load_OneBitTiff_StaysOneBitPerPixel()
    {
        var file = TestMagick.BlackOnWhite(MagickFormat.Tiff, image =>
        {
            image.ColorType = ColorType.Bilevel;
            image.Depth = 1;
            image.Settings.Compression = CompressionMethod.Group4;
        });

        var image = ImageAssert.Load(file);

        Assert.Equal((PixelLayout.Indexed, 1), (image.Layout, image.BitsPerIndex));
        Assert.Equal("CCITT G4", image.Info.Compression);
        Assert.Equal(1, image.Info.BitsPerPixel);
        ImageAssert.MaskEquals(TestMagick.InRectangle, MaskBuilder.Build(image, MaskOptions.Default));
    }

    [Fact]
    public void Load_PaletteTiff_KeepsIndicesAndBurnsTheDarkColour()
    {
        // Dark red on pale yellow: colours, so ImageMagick keeps a palette rather than writing grey.
        var file = TestMagick.Encode(
            TestMagick.Draw((x, y) => TestMagick.InRectangle(x, y) ? ((byte)90, (byte)0, (byte)0) : ((byte)255, (byte)255, (byte)200)),
            MagickFormat.Tiff,
            image => image.ColorType = ColorType.Palette);

        var image = ImageAssert.Load(file);

        Assert.Equal(PixelLayout.Indexed, image.Layout);
        Assert.Equal(2, image.Info.PaletteSize);
        Assert.Equal(image.Info.PaletteSize, image.Palette.Length);
        Assert.Contains(new Rgba32(90, 0, 0), image.Palette.ToArray());
        ImageAssert.MaskEquals(TestMagick.InRectangle, MaskBuilder.Build(image, MaskOptions.Default));
    }

    [Theory]
    [InlineData(MagickFormat.Tiff)]
    [InlineData(MagickFormat.WebP)]
    public void Load_TransparentPixels_NeverBurnEvenInverted(MagickFormat format)
    {
        // Black everywhere; the left half fully transparent.
        using var source = new MagickImage(MagickColors.Black, 16, 4);
        source.Alpha(AlphaAction.Set);
        using (var pixels = source.GetPixels())
        {
            var clear = new byte[8 * 4 * 4];
            pixels.SetArea(0, 0, 8, 4, clear);
        }

        if (format == MagickFormat.WebP)
        {
            source.Settings.SetDefine(MagickFormat.WebP, "lossless", true);
        }

        var file = source.ToByteArray(format);

        var image = ImageAssert.Load(file);

        Assert.True(image.Info.HasAlpha);
        ImageAssert.MaskEquals((x, _) => x >= 8, MaskBuilder.Build(image, MaskOptions.Default));
        ImageAssert.MaskEquals((_, _) => false, MaskBuilder.Build(image, new MaskOptions { Invert = true }));
        ImageAssert.MaskEquals((x, _) => x >= 8, MaskBuilder.Build(image, new MaskOptions { Dither = DitherMethod.FloydSteinberg }));
    }

    [Fact]
    public void Load_MidGreyJpegDithered_BurnsAboutHalf()
    {
        var file = TestMagick.Grey((_, _) => 128, MagickFormat.Jpeg);

        var mask = MaskBuilder.Build(ImageAssert.Load(file), new MaskOptions { Dither = DitherMethod.FloydSteinberg });

        Assert.InRange(mask.CountSet(), TestMagick.Width * TestMagick.Height * 4 / 10, TestMagick.Width * TestMagick.Height * 6 / 10);
    }

    [Fact]
    public void ReadInfo_Jpeg_ReportsHeaderFactsAndResolution()
    {
        var file = TestMagick.Encode(
            TestMagick.Draw((x, y) => TestMagick.InRectangle(x, y) ? ((byte)200, (byte)0, (byte)0) : ((byte)255, (byte)255, (byte)255)),
            MagickFormat.Jpeg,
            image => image.Density = new Density(300, 150, DensityUnit.PixelsPerInch));

        var info = ImageAssert.Info(file, "photo.jpg");

        Assert.Equal(
            new ImageInfo("photo.jpg", ImageFormat.Jpeg, 24, 0, 64, 32, file.Length, 300, 150, RowOrder.TopDown, "JPEG", false, false, 1),
            info);
        Assert.Equal(info, ImageAssert.Load(file, "photo.jpg").Info);
    }

    [Fact]
    public void ReadInfo_TiffInPixelsPerCentimetre_GivesDotsPerInch()
    {
        var file = TestMagick.BlackOnWhite(MagickFormat.Tiff, image =>
        {
            image.Density = new Density(100, 50, DensityUnit.PixelsPerCentimeter);
            image.Settings.Compression = CompressionMethod.LZW;
        });

        var info = ImageAssert.Info(file);

        Assert.Equal(ImageFormat.Tiff, info.Format);
        Assert.Equal("LZW", info.Compression);
        Assert.Equal(254, info.DpiX!.Value, 6);
        Assert.Equal(127, info.DpiY!.Value, 6);
        Assert.Equal(1, info.FrameCount);
    }

    [Theory]
    [InlineData(false, "VP8 (lossy)")]
    [InlineData(true, "VP8L (lossless)")]
    public void ReadInfo_WebP_NamesItsCodingAndHasNoResolution(bool lossless, string compression)
    {
        var file = TestMagick.BlackOnWhite(MagickFormat.WebP, image => image.Settings.SetDefine(MagickFormat.WebP, "lossless", lossless));

        var info = ImageAssert.Info(file);

        Assert.Equal((ImageFormat.WebP, 64, 32), (info.Format, info.Width, info.Height));
        Assert.Equal(compression, info.Compression);
        Assert.Null(info.DpiX);
        Assert.Equal(file.Length, info.FileSizeBytes);
    }

    [Fact]
    public void Load_MultiPageTiff_DecodesTheFirstPageAndCountsThemAll()
    {
        var file = TestMagick.Pages(3, MagickFormat.Tiff);

        var image = ImageAssert.Load(file);

        Assert.Equal(3, image.Info.FrameCount);
        Assert.True(image.Info.HasMoreFrames);
        Assert.Equal(8 * 8, MaskBuilder.Build(image, MaskOptions.Default).CountSet());
    }

    [Fact]
    public void Load_AnimatedWebP_DecodesTheFirstFrameAndCountsThem()
    {
        using var frames = new MagickImageCollection
        {
            TestMagick.Draw((x, y) => TestMagick.InRectangle(x, y) ? (byte)0 : (byte)255),
            TestMagick.Draw((_, _) => 255),
            TestMagick.Draw((_, _) => 0),
        };
        var file = frames.ToByteArray(MagickFormat.WebP);

        var image = ImageAssert.Load(file);

        Assert.Equal(3, image.Info.FrameCount);
        Assert.Equal("VP8X (extended)", image.Info.Compression);
        ImageAssert.MaskEquals(TestMagick.InRectangle, MaskBuilder.Build(image, MaskOptions.Default));
    }

    [Fact]
    public void Load_JpegWithExtraneousBytesBeforeAMarker_DecodesAsViewersDo()
    {
        // libjpeg warns and skips the bytes; no pixel is lost, so this warning alone does not refuse the file.
        var file = TestMagick.BlackOnWhite(MagickFormat.Jpeg);
        var scan = file.AsSpan().IndexOf((ReadOnlySpan<byte>)[0xFF, 0xDA]);
        byte[] padded = [.. file[..scan], 0x12, 0x34, 0x56, .. file[scan..]];

        var image = ImageAssert.Load(padded);

        ImageAssert.MaskEquals(TestMagick.InRectangle, MaskBuilder.Build(image, MaskOptions.Default));
    }

    [Fact]
    public void Load_TiffTurnedAQuarter_IsShownTheWayAViewerShowsIt()
    {
        // Stored 64 x 32 with orientation 6 (RightTop): shown 32 wide, 64 tall, the stored top row on the right.
        var file = TestMagick.Grey((_, y) => y == 0 ? (byte)0 : (byte)255, MagickFormat.Tiff, image => image.Orientation = Orientation.RightTop);

        var info = ImageAssert.Info(file);
        var image = ImageAssert.Load(file);

        Assert.Equal((32, 64), (info.Width, info.Height));
        Assert.Equal((32, 64), (image.Width, image.Height));
        ImageAssert.MaskEquals((x, _) => x == 31, MaskBuilder.Build(image, MaskOptions.Default));
    }

    [Fact]
    public void FromFile_JpegOnDisk_BuildsTheMaskAndReportsTheFile()
    {
        using var file = ImageAssert.Write(TestMagick.BlackOnWhite(MagickFormat.Jpeg), ".jpg");

        var mask = MaskBuilder.FromFile(file.Path, MaskOptions.Default, out var info);

        Assert.Equal(file.Path, info.Path);
        Assert.Equal(new FileInfo(file.Path).Length, info.FileSizeBytes);
        ImageAssert.MaskEquals(TestMagick.InRectangle, mask);
    }

    [Theory]
    [MemberData(nameof(Formats))]
    public void Load_CutInHalf_RefusedInOneLineNamingTheFormat(string kind)
    {
        var file = BlackOnWhite(kind);

        var ex = ImageAssert.Refused(file[..(file.Length / 2)], "cut.img");

        Assert.StartsWith("cut.img: the ", ex.Message, StringComparison.Ordinal);
        Assert.Contains(kind.StartsWith("webp", StringComparison.Ordinal) ? "WebP" : kind.ToUpperInvariant(), ex.Problem, StringComparison.Ordinal);
        Assert.DoesNotContain('\n', ex.Message);
        Assert.DoesNotContain(" @ ", ex.Problem, StringComparison.Ordinal);
        Assert.DoesNotContain("`", ex.Problem, StringComparison.Ordinal);
    }

    [Fact]
    public void Load_JpegCutInItsScan_RefusedRatherThanFilledWithGrey()
    {
        // A busy picture, cut halfway through its scan (after the SOS marker): ImageMagick alone decodes it with only a
        // warning, filling the missing rows with grey, and grey can burn.
        var file = TestMagick.Grey((x, y) => (byte)(x * y * 37), MagickFormat.Jpeg);
        var scan = file.AsSpan().IndexOf((ReadOnlySpan<byte>)[0xFF, 0xDA]);
        var cut = file[..((scan + file.Length) / 2)];
        using (var lenient = new MagickImage())
        {
            lenient.Read(cut, new MagickReadSettings { Format = MagickFormat.Jpeg });
            Assert.Equal(64u, lenient.Width);
        }

        var ex = ImageAssert.Refused(cut, "cut.jpg");

        Assert.Equal("cut.jpg: the JPEG data is corrupt or truncated (Premature end of JPEG file)", ex.Message);
    }

    [Fact]
    public void Load_TiffCutBeforeItsDirectory_SaysTruncatedWithTheOffsets()
    {
        // ImageMagick writes the directory after the pixels, so cutting the file loses the directory first.
        var file = TestMagick.BlackOnWhite(MagickFormat.Tiff);
        var directory = BitConverter.ToUInt32(file, 4);

        var ex = ImageAssert.Refused(file[..100], "cut.tif");

        Assert.Equal($"cut.tif: the file is truncated: its first TIFF directory is at offset {directory}, but the file ends after 100 bytes", ex.Message);
    }

    [Fact]
    public void Load_JpegSignatureThenGarbage_RefusedNamingTheFormat()
    {
        byte[] file = [0xFF, 0xD8, 0xFF, 0xE0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12];

        var ex = ImageAssert.Refused(file, "bad.jpg");

        Assert.Contains("JPEG", ex.Problem, StringComparison.Ordinal);
        Assert.DoesNotContain('\n', ex.Message);
        Assert.IsAssignableFrom<MagickException>(ex.InnerException);
    }

    /// <summary>Cuts and corrupts valid files many ways: every outcome must be a decoded image or a one-line <see cref="ImageLoadException"/>.</summary>
    [Theory]
    [MemberData(nameof(Formats))]
    public void Load_TruncatedOrCorruptedFile_NeverFailsWithAnythingElse(string kind)
    {
        var original = BlackOnWhite(kind);
        var random = new Random(kind.Length * 7919);
        var variants = new List<byte[]>();
        for (var length = 0; length < original.Length; length += Math.Max(1, original.Length / 40))
        {
            variants.Add(original[..length]);
        }

        for (var i = 0; i < 120; i++)
        {
            var corrupt = (byte[])original.Clone();
            for (var flips = random.Next(1, 4); flips > 0; flips--)
            {
                corrupt[random.Next(corrupt.Length)] = (byte)random.Next(256);
            }

            variants.Add(corrupt);
        }

        var refused = 0;
        foreach (var variant in variants)
        {
            try
            {
                var image = ImageAssert.Load(variant);
                var mask = MaskBuilder.Build(image, MaskOptions.Default);
                Assert.Equal((image.Width, image.Height), (mask.Width, mask.Height));
            }
            catch (ImageLoadException ex)
            {
                Assert.DoesNotContain('\n', ex.Message);
                Assert.StartsWith("test-image: ", ex.Message, StringComparison.Ordinal);
                refused++;
            }
        }

        Assert.True(refused >= 40, $"only {refused} of {variants.Count} damaged files were refused");
    }

    [Fact]
    public void Load_JpegClaiming65000Square_RefusedBeforeDecodingWithoutAllocating()
    {
        var file = TestMagick.WithJpegSize(TestMagick.BlackOnWhite(MagickFormat.Jpeg), 65000, 65000);
        _ = ImageAssert.Info(TestMagick.BlackOnWhite(MagickFormat.Jpeg));
        var before = GC.GetAllocatedBytesForCurrentThread();

        var ex = ImageAssert.Refused(file);

        var allocated = GC.GetAllocatedBytesForCurrentThread() - before;
        Assert.Contains("65000 x 65000", ex.Problem, StringComparison.Ordinal);
        Assert.True(allocated < 1 << 20, $"refusing the file allocated {allocated} bytes");
    }

    [Theory]
    [InlineData(false)]
    [InlineData(true)]
    public void Load_TinyJpegClaimingBigPicture_RefusedBeforeImageMagickFillsIt(bool progressive)
    {
        // 16000 x 16000 grey fits the limits, but 4 million 8 x 8 blocks need at least 500,000 bytes.
        var small = TestMagick.Grey((_, _) => 128, MagickFormat.Jpeg, image =>
        {
            image.ColorType = ColorType.Grayscale;
            image.Settings.Interlace = progressive ? Interlace.Plane : Interlace.NoInterlace;
        });
        var file = TestMagick.WithJpegSize(small, 16000, 16000);
        var before = GC.GetAllocatedBytesForCurrentThread();

        var ex = ImageAssert.Refused(file);

        var allocated = GC.GetAllocatedBytesForCurrentThread() - before;
        Assert.Equal($"test-image: the file is truncated: a 16000 x 16000 JPEG needs at least 500000 bytes of image data, but the file has {file.Length}", ex.Message);
        Assert.True(allocated < 1 << 20, $"refusing the file allocated {allocated} bytes");
        Assert.Equal((16000, 16000), (ImageAssert.Info(file).Width, ImageAssert.Info(file).Height));
    }

    [Theory]
    [InlineData(1_000_000u, 1_000_000u, "larger than the limit")]
    [InlineData(30_000u, 30_000u, "MB limit")]
    [InlineData(0u, 10u, "TIFF")]
    public void Load_TiffClaimingAbsurdSize_RefusedBeforeDecoding(uint width, uint height, string problem)
    {
        var tiny = TestMagick.Grey((_, _) => 0, MagickFormat.Tiff, image => image.ColorType = ColorType.Grayscale);
        var file = TestMagick.WithTiffSize(tiny, width, height);
        var before = GC.GetAllocatedBytesForCurrentThread();

        var ex = ImageAssert.Refused(file);

        var allocated = GC.GetAllocatedBytesForCurrentThread() - before;
        Assert.Contains(problem, ex.Problem, StringComparison.Ordinal);
        Assert.DoesNotContain('\n', ex.Message);
        Assert.True(allocated < 1 << 20, $"refusing the file allocated {allocated} bytes");
    }

    [Fact]
    public void Load_TinyTiffClaimingOneHugeStrip_RefusedBeforeImageMagickAllocatesTheStrip()
    {
        // 16000 x 16000 grey fits the pixel cache limit, but ImageMagick would read the one 16000-row strip into a buffer of 976 MB.
        var tiny = TestMagick.Grey((_, _) => 0, MagickFormat.Tiff, image => image.ColorType = ColorType.Grayscale);
        var file = TestMagick.WithTiffSize(tiny, 16000, 16000, rowsPerStrip: 16000);

        var ex = ImageAssert.Refused(file);

        Assert.Equal(
            "test-image: a 16000 x 16000 TIFF image needs 1464 MB to decode, more than the 1024 MB limit (its strips are read 976 MB at a time); save it with smaller strips, or as a 1-bit BMP",
            ex.Message);
    }

    [Fact]
    public void Load_TiffClaimingBigButThinStrips_GoesToImageMagickAndIsRefusedThere()
    {
        // A big claim with 16-row strips passes the size check; the missing strips are then ImageMagick's to find.
        var tiny = TestMagick.Grey((_, _) => 0, MagickFormat.Tiff, image => image.ColorType = ColorType.Grayscale);
        var file = TestMagick.WithTiffSize(tiny, 4000, 4000, rowsPerStrip: 16);

        var ex = ImageAssert.Refused(file);

        Assert.StartsWith("test-image: the TIFF ", ex.Message, StringComparison.Ordinal);
        Assert.IsAssignableFrom<MagickException>(ex.InnerException);
    }

    [Fact]
    public void Load_AnyMagickFormat_LeavesImageMagickLimitedToOurLimits()
    {
        _ = ImageAssert.Load(TestMagick.BlackOnWhite(MagickFormat.WebP));

        Assert.Equal((ulong)BitMask.MaxSide, ResourceLimits.Width);
        Assert.Equal((ulong)BitMask.MaxSide, ResourceLimits.Height);
        Assert.Equal((ulong)ImageLimits.MaxDecodedBytes, ResourceLimits.Memory);
        Assert.Equal((ulong)ImageLimits.MaxDecodedBytes, ResourceLimits.MaxMemoryRequest);
        Assert.Equal(0UL, ResourceLimits.Disk);
    }

    [Theory]
    [InlineData("Premature end of JPEG file `photo.jpg' @ warning/jpeg.c/JPEGWarningHandler/670", "Premature end of JPEG file")]
    [InlineData("InsufficientImageDataInFile `' @ error/jpeg.c/ReadOneJPEGImage/1555", "insufficient image data in file")]
    [InlineData("Maximum supported image dimension is 65500 pixels `x.jpg' @ error/jpeg.c/JPEGErrorHandler/615", "Maximum supported image dimension is 65500 pixels")]
    [InlineData("line one\nline two", "line one line two")]
    public void Describe_ImageMagickMessage_KeepsOnlyTheReasonOnOneLine(string message, string expected)
    {
        Assert.Equal(expected, MagickDecoder.Describe(message));
    }

    private static byte[] BlackOnWhite(string kind) => kind switch
    {
        "jpeg" => TestMagick.BlackOnWhite(MagickFormat.Jpeg),
        "tiff" => TestMagick.BlackOnWhite(MagickFormat.Tiff),
        "webp-lossy" => TestMagick.BlackOnWhite(MagickFormat.WebP),
        "webp-lossless" => TestMagick.BlackOnWhite(MagickFormat.WebP, image => image.Settings.SetDefine(MagickFormat.WebP, "lossless", true)),
        _ => throw new ArgumentOutOfRangeException(nameof(kind), kind, "unknown test format"),
    };
}
