using System.Buffers.Binary;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Tests.Imaging;

public class PngDecoderTests
{
    public static TheoryData<int, int, bool> ColourTypesAndDepths()
    {
        var data = new TheoryData<int, int, bool>();
        foreach (var interlaced in new[] { false, true })
        {
            foreach (var depth in new[] { 1, 2, 4, 8, 16 })
            {
                data.Add(0, depth, interlaced);
            }

            foreach (var depth in new[] { 1, 2, 4, 8 })
            {
                data.Add(3, depth, interlaced);
            }

            foreach (var type in new[] { 2, 4, 6 })
            {
                data.Add(type, 8, interlaced);
                data.Add(type, 16, interlaced);
            }
        }

        return data;
    }

    [Theory]
    [MemberData(nameof(ColourTypesAndDepths))]
    public void Load_EveryColourTypeAndDepth_ReturnsTheEncodedColours(int colourType, int depth, bool interlaced)
    {
        const int width = 13, height = 11;
        var channels = colourType switch { 0 or 3 => 1, 2 => 3, 4 => 2, _ => 4 };
        var random = new Random((colourType * 100) + depth);
        var levels = depth == 16 ? 256 : 1 << depth;
        var paletteSize = Math.Min(levels, 200);
        var palette = Enumerable.Range(0, paletteSize).Select(_ => new Rgba32((byte)random.Next(256), (byte)random.Next(256), (byte)random.Next(256))).ToArray();

        // 16-bit samples are k * 257 give or take a little, which must decode to the 8-bit k.
        var levelsUsed = colourType == 3 ? paletteSize : levels;
        var chosen = new int[width * height * channels];
        for (var i = 0; i < chosen.Length; i++)
        {
            chosen[i] = random.Next(levelsUsed);
        }

        var samples = chosen.Select(k => depth == 16 ? (k * 257) + (k == 255 ? -random.Next(100) : random.Next(100)) : k).ToArray();
        var file = new TestPng
        {
            Width = width,
            Height = height,
            ColourType = colourType,
            BitDepth = depth,
            Samples = samples,
            Palette = colourType == 3 ? palette.SelectMany(c => new[] { c.R, c.G, c.B }).ToArray() : null,
            Interlaced = interlaced,
        }.ToBytes();

        var image = ImageAssert.Load(file);

        byte Level(int k) => depth >= 8 ? (byte)k : (byte)(k * 255 / (levels - 1));
        ImageAssert.PixelsEqual(
            (x, y) =>
            {
                var s = chosen.AsSpan(((y * width) + x) * channels, channels);
                return colourType switch
                {
                    0 => new Rgba32(Level(s[0]), Level(s[0]), Level(s[0])),
                    3 => palette[s[0]],
                    2 => new Rgba32(Level(s[0]), Level(s[1]), Level(s[2])),
                    4 => new Rgba32(Level(s[0]), Level(s[0]), Level(s[0]), Level(s[1])),
                    _ => new Rgba32(Level(s[0]), Level(s[1]), Level(s[2]), Level(s[3])),
                };
            },
            image);
        Assert.Equal(interlaced, image.Info.Interlaced);
        Assert.Equal(channels * depth, image.Info.BitsPerPixel);
    }

    [Fact]
    public void Load_PaletteWithTransparency_AppliesTheAlphas()
    {
        var file = new TestPng
        {
            Width = 3,
            Height = 1,
            ColourType = 3,
            Samples = [0, 1, 2],
            Palette = [0, 0, 0, 255, 255, 255, 9, 9, 9],
            Transparency = [0, 128],
        }.ToBytes();

        var image = ImageAssert.Load(file);

        Assert.Equal(new Rgba32(0, 0, 0, 0), image.GetPixel(0, 0));
        Assert.Equal(new Rgba32(255, 255, 255, 128), image.GetPixel(1, 0));
        Assert.Equal(new Rgba32(9, 9, 9, 255), image.GetPixel(2, 0));
        Assert.True(image.Info.HasAlpha);
    }

    [Theory]
    [InlineData(8)]
    [InlineData(16)]
    public void Load_GreyWithTransparentValue_MakesOnlyThatValueTransparent(int depth)
    {
        var file = new TestPng { Width = 2, Height = 1, ColourType = 0, BitDepth = depth, Samples = [7, 8], Transparency = [0, 7] }.ToBytes();

        var image = ImageAssert.Load(file);

        Assert.Equal(0, image.GetPixel(0, 0).A);
        Assert.Equal(255, image.GetPixel(1, 0).A);
    }

    [Fact]
    public void Load_RgbWithTransparentColour_MakesOnlyThatColourTransparent()
    {
        var file = new TestPng { Width = 2, Height = 1, ColourType = 2, Samples = [1, 2, 3, 1, 2, 4], Transparency = [0, 1, 0, 2, 0, 3] }.ToBytes();

        var image = ImageAssert.Load(file);

        Assert.Equal(new Rgba32(1, 2, 3, 0), image.GetPixel(0, 0));
        Assert.Equal(new Rgba32(1, 2, 4, 255), image.GetPixel(1, 0));
    }

    [Fact]
    public void Load_InterlacedAndPlain_AgreeForEverySmallSize()
    {
        for (var width = 1; width <= 10; width++)
        {
            for (var height = 1; height <= 10; height++)
            {
                var samples = Enumerable.Range(0, width * height * 3).Select(i => (i * 37) % 256).ToArray();
                var plain = ImageAssert.Load(new TestPng { Width = width, Height = height, ColourType = 2, Samples = samples }.ToBytes());
                var interlaced = ImageAssert.Load(new TestPng { Width = width, Height = height, ColourType = 2, Samples = samples, Interlaced = true }.ToBytes());

                ImageAssert.PixelsEqual(plain.GetPixel, interlaced);
            }
        }
    }

    [Fact]
    public void Load_DataSplitOverManyIdatChunks_Decodes()
    {
        var samples = Enumerable.Range(0, 40 * 30).Select(i => i % 2).ToArray();
        var file = new TestPng { Width = 40, Height = 30, ColourType = 0, BitDepth = 1, Samples = samples, IdatChunkSize = 7 }.ToBytes();

        var image = ImageAssert.Load(file);

        ImageAssert.PixelsEqual((x, y) => samples[(y * 40) + x] == 1 ? Rgba32.White : Rgba32.Black, image);
        Assert.Equal(PixelLayout.Indexed, image.Layout);
    }

    [Theory]
    [InlineData(1, 3780u, 96.0)]
    [InlineData(0, 3780u, null)]
    public void ReadInfo_PhysicalChunk_GivesDpiOnlyInMetres(byte unit, uint pixelsPerUnit, double? expectedDpi)
    {
        var file = new TestPng { Width = 1, Height = 1, Samples = [0], Physical = (pixelsPerUnit, pixelsPerUnit, unit) }.ToBytes();

        var info = ImageAssert.Info(file);

        Assert.Equal(expectedDpi, info.DpiX is { } dpi ? Math.Round(dpi, 1) : null);
        Assert.Equal(ImageFormat.Png, info.Format);
        Assert.Equal("deflate", info.Compression);
    }

    [Fact]
    public void Load_BadChunkCrc_IsRefused()
    {
        var file = new TestPng { Width = 4, Height = 4, Samples = new int[16] }.ToBytes();
        file[^13] ^= 0x55; // the last byte of the IDAT chunk's CRC, just before the 12-byte IEND

        var ex = ImageAssert.Refused(file);

        Assert.Contains("CRC", ex.Problem, StringComparison.Ordinal);
    }

    [Fact]
    public void Load_CorruptZlib_IsRefused()
    {
        var png = new TestPng { Width = 4, Height = 4, Samples = new int[16] };
        using var file = new MemoryStream();
        var good = png.ToBytes();
        file.Write(good.AsSpan(0, 33));
        TestPng.WriteChunk(file, "IDAT", [0x78, 0x9C, 0xFF, 0xFF, 0xFF, 0xFF, 0x00, 0x11]);
        TestPng.WriteChunk(file, "IEND", []);

        var ex = ImageAssert.Refused(file.ToArray());

        Assert.Contains("corrupt", ex.Problem, StringComparison.Ordinal);
    }

    [Fact]
    public void Load_TruncatedFile_IsRefused()
    {
        var samples = Enumerable.Range(0, 64 * 64).Select(i => (i * 7919) % 256).ToArray();
        var file = new TestPng { Width = 64, Height = 64, Samples = samples }.ToBytes();

        var ex = ImageAssert.Refused(file[..(file.Length / 2)]);

        Assert.Contains("truncated", ex.Problem, StringComparison.Ordinal);
    }

    [Fact]
    public void Load_HugeHeaderWithTinyData_IsRefusedBeforeAllocating()
    {
        var file = new TestPng { Width = 1, Height = 1, Samples = [0] }.ToBytes();
        BinaryPrimitives.WriteInt32BigEndian(file.AsSpan(16), 30000);
        BinaryPrimitives.WriteInt32BigEndian(file.AsSpan(20), 30000);
        BinaryPrimitives.WriteUInt32BigEndian(file.AsSpan(29), Crc32.Compute(file.AsSpan(12, 17)));
        var before = GC.GetAllocatedBytesForCurrentThread();

        var ex = ImageAssert.Refused(file);

        Assert.Contains("cannot hold a 30000 x 30000 image", ex.Problem, StringComparison.Ordinal);
        Assert.True(GC.GetAllocatedBytesForCurrentThread() - before < 1 << 20);
    }

    [Fact]
    public void Load_FullColourAboveTheLimit_IsRefusedWithAClearMessage()
    {
        var file = new TestPng { Width = 1, Height = 1, ColourType = 2, Samples = [0, 0, 0] }.ToBytes();
        BinaryPrimitives.WriteInt32BigEndian(file.AsSpan(16), 20000);
        BinaryPrimitives.WriteInt32BigEndian(file.AsSpan(20), 20000);
        BinaryPrimitives.WriteUInt32BigEndian(file.AsSpan(29), Crc32.Compute(file.AsSpan(12, 17)));

        var ex = ImageAssert.Refused(file);

        Assert.Contains("256-megapixel limit", ex.Problem, StringComparison.Ordinal);
    }

    [Fact]
    public void Load_UnknownCriticalChunk_IsRefused()
    {
        var good = new TestPng { Width = 1, Height = 1, Samples = [0] }.ToBytes();
        using var file = new MemoryStream();
        file.Write(good.AsSpan(0, 33));
        TestPng.WriteChunk(file, "ZZZZ", [1, 2, 3]);
        file.Write(good.AsSpan(33));

        var ex = ImageAssert.Refused(file.ToArray());

        Assert.Contains("ZZZZ", ex.Problem, StringComparison.Ordinal);
    }

    [Fact]
    public void Load_AncillaryChunkItDoesNotKnow_IsSkipped()
    {
        var good = new TestPng { Width = 1, Height = 1, Samples = [255] }.ToBytes();
        using var file = new MemoryStream();
        file.Write(good.AsSpan(0, 33));
        TestPng.WriteChunk(file, "tEXt", "Comment\0hello"u8);
        file.Write(good.AsSpan(33));

        Assert.Equal(Rgba32.White, ImageAssert.Load(file.ToArray()).GetPixel(0, 0));
    }

    [Fact]
    public void Load_PaletteIndexPastThePalette_IsRefused()
    {
        var file = new TestPng { Width = 2, Height = 1, ColourType = 3, Samples = [0, 3], Palette = [0, 0, 0, 255, 255, 255] }.ToBytes();

        Assert.Contains("colour index 3", ImageAssert.Refused(file).Problem, StringComparison.Ordinal);
    }

    [Fact]
    public void Crc32_StandardCheckValue_Matches()
    {
        Assert.Equal(0xCBF43926u, Crc32.Compute("123456789"u8));
    }
}
