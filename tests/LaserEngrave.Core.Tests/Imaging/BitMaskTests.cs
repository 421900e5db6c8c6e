using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Tests.Imaging;

public class BitMaskTests
{
    [Theory]
    [InlineData(1, 1)]
    [InlineData(63, 2)]
    [InlineData(64, 3)]
    [InlineData(65, 1)]
    [InlineData(200, 7)]
    public void Indexer_SetAndGet_RoundTripsEveryPixel(int width, int height)
    {
        var mask = new BitMask(width, height);
        var random = new Random(width * 31 + height);
        var expected = new bool[width, height];
        for (var y = 0; y < height; y++)
        {
            for (var x = 0; x < width; x++)
            {
                expected[x, y] = random.Next(2) == 1;
                mask[x, y] = expected[x, y];
            }
        }

        long count = 0;
        for (var y = 0; y < height; y++)
        {
            for (var x = 0; x < width; x++)
            {
                Assert.Equal(expected[x, y], mask[x, y]);
                count += expected[x, y] ? 1 : 0;
            }
        }

        Assert.Equal(count, mask.CountSet());
    }

    [Fact]
    public void Constructor_AbsurdSize_Throws()
    {
        Assert.Throws<ArgumentOutOfRangeException>(() => new BitMask(0, 10));
        Assert.Throws<ArgumentOutOfRangeException>(() => new BitMask(BitMask.MaxSide + 1, 1));
    }

    [Fact]
    public void WordsPerRow_20000Pixels_Is313AndMaskTakes50MB()
    {
        var mask = new BitMask(20000, 20000);
        Assert.Equal(313, mask.WordsPerRow);
        Assert.Equal(313L * 20000 * 8, (long)mask.WordsPerRow * mask.Height * sizeof(ulong));
    }
}
