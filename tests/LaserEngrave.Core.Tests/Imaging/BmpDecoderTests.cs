using System.Buffers.Binary;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Tests.Imaging;

public class BmpDecoderTests
{
    private static readonly Rgba32 Grey = new(128, 128, 128);

    [Theory]
    [InlineData(1)]
    [InlineData(2)]
    [InlineData(4)]
    [InlineData(8)]
    public void Load_PaletteDepthsAndEveryPadding_ReturnsEachPixelsColour(int bits)
    {
        var palette = Enumerable.Range(0, 1 << bits).Select(i => new Rgba32((byte)i, (byte)(255 - i), (byte)(i * 7))).ToArray();
        foreach (var width in new[] { 1, 2, 3, 4, 5, 7, 8, 9, 31, 32, 33, 63, 64, 65, 70 })
        {
            var random = new Random((bits * 1000) + width);
            var indices = new int[3, width];
            for (var y = 0; y < 3; y++)
            {
                for (var x = 0; x < width; x++)
                {
                    indices[y, x] = random.Next(palette.Length);
                }
            }

            var file = new TestBmp { Width = width, Height = 3, BitsPerPixel = bits, Palette = palette, Rows = TestBmp.PackIndices(indices, bits) }.ToBytes();
            var image = ImageAssert.Load(file);

            Assert.Equal(PixelLayout.Indexed, image.Layout);
            ImageAssert.PixelsEqual((x, y) => palette[indices[y, x]], image);
        }
    }

    [Fact]
    public void Load_TopDownAndBottomUp_GiveTheSameImage()
    {
        var indices = new[,] { { 0, 1, 1 }, { 1, 0, 0 } };
        var rows = TestBmp.PackIndices(indices, 1);
        var bottomUp = ImageAssert.Load(new TestBmp { Width = 3, Height = 2, Rows = rows }.ToBytes());
        var topDown = ImageAssert.Load(new TestBmp { Width = 3, Height = 2, Rows = rows, TopDown = true }.ToBytes());

        ImageAssert.PixelsEqual((x, y) => indices[y, x] == 0 ? Rgba32.Black : Rgba32.White, bottomUp);
        ImageAssert.PixelsEqual(bottomUp.GetPixel, topDown);
        Assert.Equal(RowOrder.BottomUp, bottomUp.Info.RowOrder);
        Assert.Equal(RowOrder.TopDown, topDown.Info.RowOrder);
    }

    [Fact]
    public void Load_BottomUpFile_FirstStoredRowIsTheBottom()
    {
        // One-pixel-wide, three rows: stored bytes 0x00 (index 0, black) first, so the bottom row is black.
        var data = new byte[] { 0x00, 0, 0, 0, 0x80, 0, 0, 0, 0x80, 0, 0, 0 };
        var image = ImageAssert.Load(new TestBmp { Width = 1, Height = 3, PixelData = data }.ToBytes());

        Assert.Equal(Rgba32.White, image.GetPixel(0, 0));
        Assert.Equal(Rgba32.White, image.GetPixel(0, 1));
        Assert.Equal(Rgba32.Black, image.GetPixel(0, 2));
    }

    [Fact]
    public void Load_Rle8WithDeltaEndOfLineAndEndOfBitmap_LeavesSkippedPixelsTransparent()
    {
        byte[] rle =
        [
            0x03, 0x01, 0x00, 0x00,                         // bottom row: three of index 1, end of line
            0x00, 0x03, 0x02, 0x01, 0x02, 0x00, 0x02, 0x00, // literal 2, 1, 2 (padded), two of index 0
            0x00, 0x00,                                     // end of line
            0x00, 0x02, 0x01, 0x00, 0x02, 0x01,             // delta right 1, two of index 1
            0x00, 0x01,                                     // end of bitmap
        ];
        var palette = new[] { Rgba32.Black, Rgba32.White, Grey };
        var file = new TestBmp { Width = 5, Height = 3, BitsPerPixel = 8, Compression = 1, Palette = palette, PixelData = rle }.ToBytes();

        var image = ImageAssert.Load(file);

        var t = Rgba32.Transparent;
        Rgba32 w = Rgba32.White, b = Rgba32.Black;
        Rgba32[][] expected =
        [
            [t, w, w, t, t],
            [Grey, w, Grey, b, b],
            [w, w, w, t, t],
        ];
        ImageAssert.PixelsEqual((x, y) => expected[y][x], image);
        Assert.Equal("RLE8", image.Info.Compression);
        var inverted = MaskBuilder.Build(image, new MaskOptions { Invert = true });
        Assert.False(inverted[0, 0], "a skipped pixel must not burn, even inverted");
    }

    [Fact]
    public void Load_Rle4_SplitsBytesIntoHighThenLowNibble()
    {
        byte[] rle = [0x00, 0x03, 0x12, 0x30, 0x04, 0x45, 0x00, 0x01];
        var palette = Enumerable.Range(0, 6).Select(i => new Rgba32((byte)(i * 40), 0, 0)).ToArray();
        var file = new TestBmp { Width = 7, Height = 1, BitsPerPixel = 4, Compression = 2, Palette = palette, PixelData = rle }.ToBytes();

        var image = ImageAssert.Load(file);

        int[] expected = [1, 2, 3, 4, 5, 4, 5];
        ImageAssert.PixelsEqual((x, _) => palette[expected[x]], image);
    }

    [Theory]
    [InlineData(new byte[] { 0x06, 0x01, 0x00, 0x01 }, "passes the end")]
    [InlineData(new byte[] { 0x00, 0x02, 0x09, 0x00, 0x00, 0x01 }, "outside")]
    [InlineData(new byte[] { 0x02, 0x01, 0x00, 0x00, 0x02, 0x01, 0x00, 0x00, 0x01, 0x01 }, "past the last")]
    [InlineData(new byte[] { 0x02, 0x01, 0x00 }, "RLE data")]
    [InlineData(new byte[] { 0x00, 0x05, 0x01, 0x01 }, "truncated")]
    [InlineData(new byte[] { 0x02, 0x07, 0x00, 0x01 }, "colour index 7")]
    public void Load_CorruptRle8_IsRefused(byte[] rle, string problem)
    {
        var file = new TestBmp { Width = 5, Height = 2, BitsPerPixel = 8, Compression = 1, Palette = [Rgba32.Black, Rgba32.White], PixelData = rle }.ToBytes();

        var ex = ImageAssert.Refused(file);

        Assert.Contains(problem, ex.Problem, StringComparison.Ordinal);
    }

    [Fact]
    public void Load_16Bit565_ScalesFullChannelsTo255()
    {
        ushort[] pixels = [0xFFFF, 0xF800, 0x07E0, 0x001F, 0x0000, 0x8410];
        var data = new byte[12];
        for (var i = 0; i < pixels.Length; i++)
        {
            BinaryPrimitives.WriteUInt16LittleEndian(data.AsSpan(2 * i), pixels[i]);
        }

        var file = new TestBmp { Width = 6, Height = 1, BitsPerPixel = 16, Compression = 3, Masks = [0xF800, 0x07E0, 0x001F], PixelData = data }.ToBytes();
        var image = ImageAssert.Load(file);

        Rgba32[] expected = [Rgba32.White, new(255, 0, 0), new(0, 255, 0), new(0, 0, 255), Rgba32.Black, new(132, 130, 132)];
        ImageAssert.PixelsEqual((x, _) => expected[x], image);
        Assert.Equal("BITFIELDS", image.Info.Compression);
    }

    [Fact]
    public void Load_16BitDefault555_IgnoresTheUnusedTopBit()
    {
        var data = new byte[4];
        BinaryPrimitives.WriteUInt16LittleEndian(data, 0xFFFF);
        BinaryPrimitives.WriteUInt16LittleEndian(data.AsSpan(2), 0x8000);
        var image = ImageAssert.Load(new TestBmp { Width = 2, Height = 1, BitsPerPixel = 16, PixelData = data }.ToBytes());

        Assert.Equal(Rgba32.White, image.GetPixel(0, 0));
        Assert.Equal(Rgba32.Black, image.GetPixel(1, 0));
    }

    [Fact]
    public void Load_24Bit_StoresBlueGreenRed()
    {
        byte[] data = [10, 20, 30, 40, 50, 60, 0, 0];
        var image = ImageAssert.Load(new TestBmp { Width = 2, Height = 1, BitsPerPixel = 24, PixelData = data }.ToBytes());

        Assert.Equal(new Rgba32(30, 20, 10), image.GetPixel(0, 0));
        Assert.Equal(new Rgba32(60, 50, 40), image.GetPixel(1, 0));
        Assert.False(image.Info.HasAlpha);
    }

    [Fact]
    public void Load_32BitV5WithAlphaMask_KeepsAlpha()
    {
        var data = new byte[8];
        BinaryPrimitives.WriteUInt32LittleEndian(data, 0x00_0000FF);
        BinaryPrimitives.WriteUInt32LittleEndian(data.AsSpan(4), 0xFF_00FF00);
        var file = new TestBmp
        {
            Width = 2,
            Height = 1,
            BitsPerPixel = 32,
            HeaderSize = 124,
            Compression = 3,
            Masks = [0x000000FF, 0x0000FF00, 0x00FF0000, 0xFF000000],
            PixelData = data,
        }.ToBytes();

        var image = ImageAssert.Load(file);

        Assert.Equal(new Rgba32(255, 0, 0, 0), image.GetPixel(0, 0));
        Assert.Equal(new Rgba32(0, 255, 0, 255), image.GetPixel(1, 0));
        Assert.True(image.Info.HasAlpha);
    }

    [Fact]
    public void Load_32BitWithoutBitfields_TreatsFourthByteAsUnused()
    {
        byte[] data = [0, 0, 0, 0, 0, 0, 0, 77];
        var image = ImageAssert.Load(new TestBmp { Width = 2, Height = 1, BitsPerPixel = 32, PixelData = data }.ToBytes());

        Assert.Equal(Rgba32.Black, image.GetPixel(0, 0));
        Assert.Equal(Rgba32.Black, image.GetPixel(1, 0));
    }

    [Fact]
    public void Load_Os2Version1Header_ReadsThreeBytePalette()
    {
        var palette = new[] { new Rgba32(200, 10, 20), new Rgba32(5, 6, 7) };
        var file = new TestBmp { Width = 2, Height = 1, HeaderSize = 12, Palette = palette, Rows = [[0x40]] }.ToBytes();

        var image = ImageAssert.Load(file);

        Assert.Equal(palette[0], image.GetPixel(0, 0));
        Assert.Equal(palette[1], image.GetPixel(1, 0));
        Assert.Null(image.Info.DpiX);
    }

    [Fact]
    public void ReadInfo_PelsPerMetre_BecomesDotsPerInch()
    {
        var file = new TestBmp { Width = 9, Height = 4, PelsPerMetreX = 3780, PelsPerMetreY = 0, Rows = new byte[4][].Select(_ => new byte[2]).ToArray() }.ToBytes();

        var info = ImageAssert.Info(file, "x.bmp");

        Assert.Equal(96.012, info.DpiX!.Value, 6);
        Assert.Null(info.DpiY);
        Assert.Equal(new ImageInfo("x.bmp", ImageFormat.Bmp, 1, 2, 9, 4, file.Length, info.DpiX, null, RowOrder.BottomUp, "none", false), info);
    }

    [Fact]
    public void Load_HeaderClaimsMorePixelsThanTheFileHolds_IsRefusedBeforeAllocating()
    {
        var file = new TestBmp { Width = 30000, Height = 30000, PixelData = new byte[100] }.ToBytes();
        var before = GC.GetAllocatedBytesForCurrentThread();

        var ex = ImageAssert.Refused(file);

        Assert.Contains("truncated", ex.Problem, StringComparison.Ordinal);
        Assert.True(GC.GetAllocatedBytesForCurrentThread() - before < 1 << 20);
    }

    [Fact]
    public void Load_IndexPastThePalette_IsRefused()
    {
        var file = new TestBmp { Width = 2, Height = 1, BitsPerPixel = 4, Palette = [Rgba32.Black, Rgba32.White, Grey], Rows = [[0x05]] }.ToBytes();

        var ex = ImageAssert.Refused(file);

        Assert.Contains("colour index 5", ex.Problem, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData(0, 1, "width")]
    [InlineData(4, 0, "height")]
    public void Load_ZeroDimension_IsRefused(int width, int height, string problem)
    {
        var file = new TestBmp { Width = width, Height = height, PixelData = new byte[8] }.ToBytes();

        Assert.Contains(problem, ImageAssert.Refused(file).Problem, StringComparison.Ordinal);
    }

    [Fact]
    public void Load_EmbeddedJpegCut_IsRefusedNamingTheJpeg()
    {
        var file = new TestBmp { Width = 2, Height = 2, BitsPerPixel = 0, Compression = 4, PixelData = [0xFF, 0xD8, 0xFF, 0xE0] }.ToBytes();

        var ex = ImageAssert.Refused(file, "photo.bmp");

        Assert.StartsWith("photo.bmp: the JPEG data is corrupt or truncated (", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Load_EmbeddedJpeg_DecodesTheJpegWithTheBmpHeaderFacts()
    {
        var jpeg = TestMagick.BlackOnWhite(ImageMagick.MagickFormat.Jpeg);
        var file = new TestBmp { Width = TestMagick.Width, Height = TestMagick.Height, BitsPerPixel = 0, Compression = 4, PixelData = jpeg }.ToBytes();

        var image = ImageAssert.Load(file, "photo.bmp");

        Assert.Equal((ImageFormat.Bmp, "JPEG"), (image.Info.Format, image.Info.Compression));
        Assert.Equal((TestMagick.Width, TestMagick.Height), (image.Info.Width, image.Info.Height));
        Assert.Equal(image.Info, ImageAssert.Info(file, "photo.bmp"));
        ImageAssert.MaskEquals(TestMagick.InRectangle, MaskBuilder.Build(image, MaskOptions.Default));
    }

    [Fact]
    public void Load_EmbeddedPng_DecodesThePng()
    {
        var png = new TestPng { Width = 2, Height = 1, ColourType = 2, Samples = [255, 0, 0, 0, 0, 255] }.ToBytes();
        var file = new TestBmp { Width = 2, Height = 1, BitsPerPixel = 0, HeaderSize = 124, Compression = 5, PixelData = png }.ToBytes();

        var image = ImageAssert.Load(file);

        Assert.Equal(new Rgba32(255, 0, 0), image.GetPixel(0, 0));
        Assert.Equal(new Rgba32(0, 0, 255), image.GetPixel(1, 0));
        Assert.Equal(ImageFormat.Bmp, image.Info.Format);
        Assert.Equal("PNG", image.Info.Compression);
    }
}
