using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Benchmarks;

/// <summary>A QR-code-like mask (finder squares, random modules, a quiet zone) scaled up to any size: the typical content of a job.</summary>
public static class QrLikeMask
{
    public static BitMask Create(int side, int modules = 41, int seed = 1)
    {
        const int Quiet = 4;
        var rng = new Random(seed);
        var total = modules + (2 * Quiet);
        var dark = new bool[total, total];
        for (var y = 0; y < modules; y++)
        {
            for (var x = 0; x < modules; x++)
            {
                dark[x + Quiet, y + Quiet] = Finder(x, y, modules) ?? rng.Next(2) == 0;
            }
        }

        // Pixel rows repeat within a module row, so each distinct row is built once and copied.
        var mask = new BitMask(side, side);
        var previousModuleRow = -1;
        for (var y = 0; y < side; y++)
        {
            var moduleRow = (int)((long)y * total / side);
            if (moduleRow == previousModuleRow)
            {
                mask.ReadRow(y - 1).CopyTo(mask.Row(y));
                continue;
            }

            previousModuleRow = moduleRow;
            for (var x = 0; x < side; x++)
            {
                mask[x, y] = dark[(int)((long)x * total / side), moduleRow];
            }
        }

        return mask;
    }

    /// <summary>The fixed modules of the three finder squares (7 x 7 with their white separators), or null elsewhere.</summary>
    private static bool? Finder(int x, int y, int modules)
    {
        foreach (var (fx, fy) in new[] { (0, 0), (modules - 7, 0), (0, modules - 7) })
        {
            int dx = x - fx, dy = y - fy;
            if (dx is >= -1 and <= 7 && dy is >= -1 and <= 7)
            {
                if (dx is -1 or 7 || dy is -1 or 7)
                {
                    return false;
                }

                var ring = Math.Max(Math.Abs(dx - 3), Math.Abs(dy - 3));
                return ring != 2;
            }
        }

        return null;
    }
}
