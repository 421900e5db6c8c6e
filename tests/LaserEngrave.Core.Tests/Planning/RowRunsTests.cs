using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Planning;

public class RowRunsTests
{
    [Fact]
    public void Find_RandomRows_MatchesAPixelByPixelScan()
    {
        var rng = new Random(2024);
        var runs = new int[2];
        for (var iteration = 0; iteration < 400; iteration++)
        {
            var width = iteration % 5 == 0 ? 64 * (1 + rng.Next(4)) : 1 + rng.Next(300);
            var mask = new BitMask(width, 1);
            var density = iteration % 7 == 0 ? 1.0 : iteration % 11 == 0 ? 0.0 : rng.NextDouble();
            var meanRun = 1 + rng.Next(100);
            var black = rng.NextDouble() < density;
            for (var x = 0; x < width; x++)
            {
                if (rng.Next(meanRun) == 0)
                {
                    black = rng.NextDouble() < density;
                }

                mask[x, 0] = black;
            }

            var count = RowRuns.Find(mask.ReadRow(0), ref runs);
            Assert.Equal(ScanPixels(mask), Enumerable.Range(0, count).Select(i => (runs[2 * i], runs[(2 * i) + 1])).ToList());
        }
    }

    [Fact]
    public void Find_AllBlackRowOfWholeWords_EndsAtTheWidth()
    {
        var mask = new BitMask(128, 1);
        mask.Row(0).Fill(ulong.MaxValue);
        var runs = new int[2];
        Assert.Equal(1, RowRuns.Find(mask.ReadRow(0), ref runs));
        Assert.Equal((0, 128), (runs[0], runs[1]));
    }

    [Fact]
    public void Find_BlankRow_FindsNothing()
    {
        var runs = new int[2];
        Assert.Equal(0, RowRuns.Find(new BitMask(1000, 1).ReadRow(0), ref runs));
    }

    private static List<(int, int)> ScanPixels(BitMask mask)
    {
        var result = new List<(int, int)>();
        var x = 0;
        while (x < mask.Width)
        {
            if (!mask[x, 0])
            {
                x++;
                continue;
            }

            var start = x;
            while (x < mask.Width && mask[x, 0])
            {
                x++;
            }

            result.Add((start, x));
        }

        return result;
    }
}
