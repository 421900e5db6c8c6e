using LaserEngrave.Core.Alignment;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Tests.Alignment;

public class MaskResamplerTests
{
    [Fact]
    public void Resample_QuarterTurn_IsTheMaskTurnedPixelForPixel()
    {
        var mask = Letter(37, 23);

        var aligned = MaskResampler.Resample(mask, 10, new RigidTransform(Math.PI / 2, 3, 4));

        // +x turns to +y: job pixel (x, y) lands at new pixel (H - 1 - y, x); the grid spans x from 3 - H p to 3.
        Assert.Equal((23, 37), (aligned.Mask.Width, aligned.Mask.Height));
        for (var y = 0; y < mask.Height; y++)
        {
            for (var x = 0; x < mask.Width; x++)
            {
                Assert.True(mask[x, y] == aligned.Mask[mask.Height - 1 - y, x], $"pixel ({x}, {y})");
            }
        }

        Assert.Equal(3 - 0.23, aligned.OriginXMm, 9);
        Assert.Equal(4, aligned.OriginYMm, 9);
    }

    [Fact]
    public void Resample_ThirtyDegrees_EveryJobPixelCentreLandsOnABurntPixel()
    {
        var mask = Letter(120, 80);
        var angle = 30 * Math.PI / 180;
        const double P = 0.01;

        var aligned = MaskResampler.Resample(mask, 10, new RigidTransform(angle, 5, 2));

        // Each burnt job pixel's centre, turned by hand, falls in the new grid on a burnt pixel or next to one.
        var (s, c) = (Math.Sin(angle), Math.Cos(angle));
        var missed = 0;
        var burnt = 0;
        for (var y = 0; y < mask.Height; y++)
        {
            for (var x = 0; x < mask.Width; x++)
            {
                if (!mask[x, y])
                {
                    continue;
                }

                burnt++;
                double jx = (x + 0.5) * P, jy = (y + 0.5) * P;
                var sx = 5 + (c * jx) - (s * jy) - aligned.OriginXMm;
                var sy = 2 + (s * jx) + (c * jy) - aligned.OriginYMm;
                int col = (int)Math.Floor(sx / P), row = (int)Math.Floor(sy / P);
                var near = false;
                for (var dy = -1; dy <= 1 && !near; dy++)
                {
                    for (var dx = -1; dx <= 1 && !near; dx++)
                    {
                        int cx = col + dx, cy = row + dy;
                        near = cx >= 0 && cy >= 0 && cx < aligned.Mask.Width && cy < aligned.Mask.Height && aligned.Mask[cx, cy];
                    }
                }

                missed += near ? 0 : 1;
            }
        }

        Assert.Equal(0, missed);

        // Area is kept: a rotation preserves it, nearest neighbour to within the outline's pixels.
        Assert.InRange(aligned.Mask.CountSet(), burnt * 0.93, burnt * 1.07);

        // The bounding box of a 1.2 x 0.8 mm job turned 30°: 1.2 cos + 0.8 sin by 1.2 sin + 0.8 cos.
        Assert.Equal((int)Math.Ceiling(((1.2 * c) + (0.8 * s)) / P), aligned.Mask.Width);
        Assert.Equal((int)Math.Ceiling(((1.2 * s) + (0.8 * c)) / P), aligned.Mask.Height);
        Assert.Equal(5 - (0.8 * s), aligned.OriginXMm, 9);
        Assert.Equal(2, aligned.OriginYMm, 9);
    }

    [Fact]
    public void Resample_NoRotation_SameMaskAtTheTranslation()
    {
        var mask = Letter(64, 40);

        var aligned = MaskResampler.Resample(mask, 25, new RigidTransform(0, 7.5, 2.25));

        Assert.Equal((7.5, 2.25), (aligned.OriginXMm, aligned.OriginYMm));
        Assert.All(Enumerable.Range(0, mask.Height), y => Assert.True(mask.ReadRow(y).SequenceEqual(aligned.Mask.ReadRow(y))));
    }

    /// <summary>An F: asymmetric, so a wrong turn or mirror shows.</summary>
    private static BitMask Letter(int width, int height)
    {
        var mask = new BitMask(width, height);
        for (var y = 2; y < height - 2; y++)
        {
            for (var x = 2; x < width - 2; x++)
            {
                var stem = x < 2 + (width / 6);
                var top = y < 2 + (height / 6);
                var middle = y >= height / 2 && y < (height / 2) + (height / 8) && x < width * 2 / 3;
                mask[x, y] = stem || top || middle;
            }
        }

        return mask;
    }
}
