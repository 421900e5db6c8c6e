using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Tests.Planning;

/// <summary>Masks and geometries built in code for the planning tests.</summary>
internal static class TestMasks
{
    public const double Microstep = 0.09921875;

    /// <summary>A mask from text rows: '#' burns, anything else does not.</summary>
    public static BitMask FromRows(params string[] rows)
    {
        var mask = new BitMask(rows[0].Length, rows.Length);
        for (var y = 0; y < rows.Length; y++)
        {
            for (var x = 0; x < rows[y].Length; x++)
            {
                mask[x, y] = rows[y][x] == '#';
            }
        }

        return mask;
    }

    /// <summary>A random mask of runs of random length, with some rows left blank and some pixels flipped singly.</summary>
    public static BitMask Random(Random rng, int width, int height)
    {
        var mask = new BitMask(width, height);
        var meanRun = 1 + rng.Next(12);
        var blankChance = rng.NextDouble() * 0.4;
        for (var y = 0; y < height; y++)
        {
            if (rng.NextDouble() < blankChance)
            {
                continue;
            }

            var black = rng.Next(2) == 0;
            var x = 0;
            while (x < width)
            {
                var length = 1 + rng.Next(2 * meanRun);
                for (var end = Math.Min(width, x + length); x < end; x++)
                {
                    mask[x, y] = black;
                }

                black = !black;
            }
        }

        return mask;
    }

    /// <summary>A geometry with an integer pitch and origin and room to spare on the stage.</summary>
    public static JobGeometry Geometry(BitMask mask, double pitch = 1000, double ox = 0, double oy = 0, long travel = 100_000_000) =>
        new(mask.Width, mask.Height, pitch, ox, oy, Microstep, travel, travel);
}
