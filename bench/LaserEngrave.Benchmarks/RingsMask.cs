using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Benchmarks;

/// <summary>
/// Concentric black and white rings, each <c>ring</c> pixels wide, black from the centre: the same mask as
/// tools/make-rings.py writes (a pixel is black when its centre lies in a black ring). At 20000 px and 20 px rings its
/// plan has 13 M moves, every gap flown: the heaviest input for the planner and the estimate.
/// </summary>
public static class RingsMask
{
    public static BitMask Create(int side = 20_000, double ring = 20)
    {
        var mask = new BitMask(side, side);
        var c = side / 2.0;
        var edges = new List<int>();
        for (var y = 0; y < side; y++)
        {
            var dy = y + 0.5 - c;
            var kMin = (int)Math.Floor(Math.Abs(dy) / ring);
            var kMax = (int)Math.Floor(Math.Sqrt((c * c) + (dy * dy)) / ring) + 1;

            // Where each ring boundary (radius k ring) crosses the row, left of the centre then right of it.
            var half = new List<double>();
            for (var k = kMin + 1; k <= kMax; k++)
            {
                var r = k * ring;
                if (r * r > dy * dy)
                {
                    half.Add(Math.Sqrt((r * r) - (dy * dy)));
                }
            }

            edges.Clear();
            for (var i = half.Count - 1; i >= 0; i--)
            {
                edges.Add(Math.Clamp((int)Math.Floor(c - half[i] - 0.5) + 1, 0, side));
            }

            foreach (var h in half)
            {
                edges.Add(Math.Clamp((int)Math.Ceiling(c + h - 0.5), 0, side));
            }

            var black = half.Count % 2 == 0 ? kMin % 2 == 0 : kMin % 2 != 0;
            var row = mask.Row(y);
            var x = 0;
            foreach (var edge in edges.Append(side))
            {
                if (black)
                {
                    for (var i = x; i < edge; i++)
                    {
                        row[i >> 6] |= 1UL << (i & 63);
                    }
                }

                x = Math.Max(x, edge);
                black = !black;
            }
        }

        return mask;
    }
}
