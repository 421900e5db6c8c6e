using System.Diagnostics;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Tests.Imaging;

/// <summary>The BMP suite: good files decode to their reference pictures, bad ones are refused or decoded without harm.</summary>
public class BmpSuiteTests
{
    /// <summary>q/ files whose mask legitimately differs from every reference shown for them, and why.</summary>
    private static readonly Dictionary<string, string> KnownDifferences = new()
    {
        ["q/rgb24prof2.bmp"] = "its red and green are swapped and only its embedded ICC profile swaps them back; colour profiles are not applied",
    };

    public static TheoryData<string> GoodFiles => BmpSuite.Files("g");

    public static TheoryData<string> QuestionableFiles => BmpSuite.Files("q");

    public static TheoryData<string> BadFiles => BmpSuite.Files("b");

    [Theory]
    [MemberData(nameof(GoodFiles))]
    public void Load_GoodFile_MaskEqualsReferenceRendering(string file)
    {
        var image = ImageLoader.Load(BmpSuite.PathOf(file));
        var mask = MaskBuilder.Build(image, MaskOptions.Default);

        var references = BmpSuite.References(file);
        Assert.NotEmpty(references);
        Assert.True(
            MatchesAnyReference(mask, references, out var report),
            $"{file}: the 1-bit mask matches none of its references: {report}");
    }

    [Theory]
    [MemberData(nameof(GoodFiles))]
    public void ReadInfo_GoodFile_AgreesWithDecodedImage(string file)
    {
        var info = ImageLoader.ReadInfo(BmpSuite.PathOf(file));
        var image = ImageLoader.Load(BmpSuite.PathOf(file));

        Assert.Equal(info, image.Info);
        Assert.Equal(ImageFormat.Bmp, info.Format);
        Assert.Equal((image.Width, image.Height), (info.Width, info.Height));
        Assert.Equal(new FileInfo(BmpSuite.PathOf(file)).Length, info.FileSizeBytes);
        Assert.Equal(info.BitsPerPixel <= 8, info.PaletteSize > 0);
    }

    [Theory]
    [MemberData(nameof(GoodFiles))]
    public void FromFile_GoodFile_EqualsLoadThenBuild(string file)
    {
        var path = BmpSuite.PathOf(file);
        foreach (var options in new[] { MaskOptions.Default, new MaskOptions { Invert = true, ThresholdPercent = 30 } })
        {
            var direct = MaskBuilder.FromFile(path, options, out var info);
            var built = MaskBuilder.Build(ImageLoader.Load(path), options);

            Assert.True(direct.ContentEquals(built), $"{file} with {options}");
            Assert.Equal(ImageLoader.ReadInfo(path), info);
        }
    }

    [Theory]
    [MemberData(nameof(QuestionableFiles))]
    public void Load_QuestionableFile_DecodesToAReferenceOrIsRefused(string file)
    {
        LoadedImage image;
        try
        {
            image = ImageLoader.Load(BmpSuite.PathOf(file));
        }
        catch (ImageLoadException ex)
        {
            AssertOneLine(ex, file);
            return;
        }

        var mask = MaskBuilder.Build(image, MaskOptions.Default);
        var references = BmpSuite.References(file);
        if (references.Count == 0 || KnownDifferences.ContainsKey(file))
        {
            Assert.Equal((image.Info.Width, image.Info.Height), (mask.Width, mask.Height));
            return;
        }

        Assert.True(MatchesAnyReference(mask, references, out var report), $"{file}: decoded, but matches none of its references: {report}");
    }

    [Theory]
    [MemberData(nameof(BadFiles))]
    public void Load_BadFile_IsRefusedOrDecodedWithoutHarm(string file)
    {
        var path = BmpSuite.PathOf(file);
        try
        {
            var image = ImageLoader.Load(path);
            var mask = MaskBuilder.Build(image, MaskOptions.Default);
            Assert.Equal((image.Width, image.Height), (mask.Width, mask.Height));
            Assert.InRange(image.Width * (long)image.Height, 1, 1L << 20);
        }
        catch (ImageLoadException ex)
        {
            AssertOneLine(ex, file);
        }

        // The one-call mask path must behave the same.
        try
        {
            MaskBuilder.FromFile(path, MaskOptions.Default, out _);
        }
        catch (ImageLoadException ex)
        {
            AssertOneLine(ex, file);
        }
    }

    [Theory]
    [MemberData(nameof(GoodFiles))]
    public void Load_GoodFileCutOrCorrupted_IsRefusedOrDecodedNeverAnythingElse(string file)
    {
        var original = File.ReadAllBytes(BmpSuite.PathOf(file));
        var random = new Random(original.Length);
        for (var i = 0; i < 200; i++)
        {
            var variant = i % 4 == 0 ? original[..random.Next(original.Length)] : (byte[])original.Clone();
            if (i % 4 != 0)
            {
                // Corrupt the headers and palette most of the time, where a wrong value changes the most.
                var limit = random.Next(2) == 0 ? Math.Min(variant.Length, 1100) : variant.Length;
                variant[random.Next(limit)] = (byte)random.Next(256);
            }

            try
            {
                MaskBuilder.Build(ImageLoader.Load(new MemoryStream(variant), file), MaskOptions.Default);
            }
            catch (ImageLoadException ex)
            {
                Assert.DoesNotContain('\n', ex.Message);
            }
        }
    }

    [Fact]
    public void Load_ReallyBig_IsRefusedWithoutAllocating()
    {
        var path = BmpSuite.PathOf("b/reallybig.bmp");
        var before = GC.GetAllocatedBytesForCurrentThread();

        var ex = Assert.Throws<ImageLoadException>(() => ImageLoader.Load(path));

        var allocated = GC.GetAllocatedBytesForCurrentThread() - before;
        Assert.Contains("3000000 x 2000000", ex.Message, StringComparison.Ordinal);
        Assert.True(allocated < 1 << 20, $"refusing reallybig.bmp allocated {allocated} bytes");
    }

    [Theory]
    [InlineData("b/shortfile.bmp", "truncated")]
    [InlineData("b/badplanes.bmp", "planes")]
    [InlineData("b/badbitcount.bmp", "30000 bits per pixel")]
    [InlineData("b/badheadersize.bmp", "header size 66")]
    [InlineData("b/badpalettesize.bmp", "palette")]
    [InlineData("b/badwidth.bmp", "width -127")]
    [InlineData("b/rletopdown.bmp", "top-down")]
    [InlineData("b/badrle.bmp", "RLE")]
    [InlineData("b/badrle4bis.bmp", "RLE")]
    [InlineData("b/pal8badindex.bmp", "colour index")]
    [InlineData("q/rgba64.bmp", "64-bit")]
    public void Load_KnownBadFile_NamesTheProblem(string file, string problem)
    {
        var ex = Assert.Throws<ImageLoadException>(() => ImageLoader.Load(BmpSuite.PathOf(file)));

        Assert.Contains(problem, ex.Problem, StringComparison.Ordinal);
        Assert.StartsWith(BmpSuite.PathOf(file) + ": ", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void References_SharedPicture_AreFoundForEveryGoodFile()
    {
        // Several g/ files share a picture (pal4rle shows pal4.png, pal8os2 shows pal8.png): the HTML, not the name, decides.
        Assert.Equal([Path.Combine(BmpSuite.Root, "html", "pal4.png")], BmpSuite.References("g/pal4rle.bmp"));
        Assert.Equal([Path.Combine(BmpSuite.Root, "html", "pal8.png")], BmpSuite.References("g/pal8os2.bmp"));
        Assert.Equal(2, BmpSuite.References("g/pal8nonsquare.bmp").Count);
    }

    [Fact]
    public void FromFile_OneBitPalettes_BurnTheBlackWhicheverIndexItHas()
    {
        // pal1.bmp has black first, pal1wb.bmp white first; they show the same picture, so the same pixels burn.
        var blackFirst = MaskBuilder.FromFile(BmpSuite.PathOf("g/pal1.bmp"), MaskOptions.Default, out _);
        var whiteFirst = MaskBuilder.FromFile(BmpSuite.PathOf("g/pal1wb.bmp"), MaskOptions.Default, out _);

        Assert.True(blackFirst.ContentEquals(whiteFirst));
        Assert.InRange(blackFirst.CountSet(), 1, (blackFirst.Width * (long)blackFirst.Height) - 1);
    }

    private static bool MatchesAnyReference(BitMask mask, IReadOnlyList<string> references, out string report)
    {
        var notes = new List<string>();
        foreach (var reference in references)
        {
            var expected = MaskBuilder.Build(ImageLoader.Load(reference), MaskOptions.Default);
            if (expected.Width != mask.Width || expected.Height != mask.Height)
            {
                notes.Add($"{Path.GetFileName(reference)} is {expected.Width} x {expected.Height}, the file {mask.Width} x {mask.Height}");
                continue;
            }

            if (expected.ContentEquals(mask))
            {
                report = string.Empty;
                return true;
            }

            notes.Add($"{Path.GetFileName(reference)} differs in {Differences(mask, expected)} pixels");
        }

        report = string.Join("; ", notes);
        return false;
    }

    private static long Differences(BitMask a, BitMask b)
    {
        long n = 0;
        for (var y = 0; y < a.Height; y++)
        {
            for (var x = 0; x < a.Width; x++)
            {
                n += a[x, y] != b[x, y] ? 1 : 0;
            }
        }

        return n;
    }

    private static void AssertOneLine(ImageLoadException ex, string file)
    {
        Debug.Assert(ex.Message is not null);
        Assert.DoesNotContain('\n', ex.Message);
        Assert.StartsWith(BmpSuite.PathOf(file) + ": ", ex.Message, StringComparison.Ordinal);
        Assert.False(string.IsNullOrWhiteSpace(ex.Problem));
    }
}
