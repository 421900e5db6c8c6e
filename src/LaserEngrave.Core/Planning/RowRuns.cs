using System.Numerics;
using System.Runtime.CompilerServices;

namespace LaserEngrave.Core.Planning;

/// <summary>Finds the runs of set pixels in a packed mask row with whole-word bit operations.</summary>
internal static class RowRuns
{
    /// <summary>
    /// Writes each run [start, end) of set bits as the pair runs[2i], runs[2i + 1], in ascending order, growing
    /// <paramref name="runs"/> when needed; returns the number of runs.
    /// </summary>
    /// <remarks>
    /// Relies on <see cref="Imaging.BitMask"/>'s guarantee that bits past the width are zero, so a run can only end past
    /// the last word when the width is a multiple of 64, and then it ends exactly at the width.
    /// </remarks>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    public static int Find(ReadOnlySpan<ulong> words, ref int[] runs)
    {
        if (words.IsEmpty)
        {
            return 0;
        }

        var count = 0;
        var index = 0;
        var word = words[0];
        while (true)
        {
            if (word == 0)
            {
                // Whole blank words are skipped in one vectorised search.
                var next = words[(index + 1)..].IndexOfAnyExcept(0UL);
                if (next < 0)
                {
                    return count;
                }

                index += next + 1;
                word = words[index];
            }

            var startBit = BitOperations.TrailingZeroCount(word);
            var start = (index << 6) + startBit;

            // The run ends at the first clear bit at or after its start: the lowest set bit of the complement.
            var clear = ~word & (ulong.MaxValue << startBit);
            if (clear == 0)
            {
                // Whole black words are skipped in one vectorised search too.
                var next = words[(index + 1)..].IndexOfAnyExcept(ulong.MaxValue);
                if (next < 0)
                {
                    Add(ref runs, ref count, start, words.Length << 6);
                    return count;
                }

                index += next + 1;
                clear = ~words[index];
            }

            var endBit = BitOperations.TrailingZeroCount(clear);
            Add(ref runs, ref count, start, (index << 6) + endBit);
            word = words[index] & (ulong.MaxValue << endBit);
        }
    }

    private static void Add(ref int[] runs, ref int count, int start, int end)
    {
        if ((count * 2) + 2 > runs.Length)
        {
            Array.Resize(ref runs, Math.Max(16, runs.Length * 2));
        }

        runs[count * 2] = start;
        runs[(count * 2) + 1] = end;
        count++;
    }
}
