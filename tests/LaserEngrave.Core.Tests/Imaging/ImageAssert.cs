using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Tests.Imaging;

/// <summary>Shared helpers: load from bytes, write temporary files, compare images.</summary>
internal static class ImageAssert
{
    public static LoadedImage Load(byte[] file, string name = "test-image") => ImageLoader.Load(new MemoryStream(file), name);

    public static ImageInfo Info(byte[] file, string name = "test-image") => ImageLoader.ReadInfo(new MemoryStream(file), name);

    public static ImageLoadException Refused(byte[] file, string name = "test-image") =>
        Assert.Throws<ImageLoadException>(() => ImageLoader.Load(new MemoryStream(file), name));

    /// <summary>Writes <paramref name="file"/> to a fresh temporary path, removed when the returned handle is disposed.</summary>
    public static TemporaryFile Write(byte[] file, string extension = ".bin")
    {
        var path = Path.Combine(Path.GetTempPath(), $"laserengrave-{Guid.NewGuid():N}{extension}");
        File.WriteAllBytes(path, file);
        return new TemporaryFile(path);
    }

    public static void PixelsEqual(Func<int, int, Rgba32> expected, LoadedImage image)
    {
        for (var y = 0; y < image.Height; y++)
        {
            for (var x = 0; x < image.Width; x++)
            {
                var want = expected(x, y);
                var got = image.GetPixel(x, y);
                if (want != got)
                {
                    Assert.Fail($"pixel ({x}, {y}) of {image.Width} x {image.Height}: expected {want}, got {got}");
                }
            }
        }
    }

    public static void MaskEquals(Func<int, int, bool> expected, BitMask mask)
    {
        for (var y = 0; y < mask.Height; y++)
        {
            for (var x = 0; x < mask.Width; x++)
            {
                if (expected(x, y) != mask[x, y])
                {
                    Assert.Fail($"mask pixel ({x}, {y}) of {mask.Width} x {mask.Height}: expected {expected(x, y)}");
                }
            }
        }

        // Bits past the width must stay clear so word-wise planning never sees phantom pixels.
        for (var y = 0; y < mask.Height; y++)
        {
            Assert.Equal(0UL, mask.ReadRow(y)[^1] & ~mask.LastWordMask);
        }
    }

    internal sealed class TemporaryFile(string path) : IDisposable
    {
        public string Path { get; } = path;

        public void Dispose() => File.Delete(Path);
    }
}
