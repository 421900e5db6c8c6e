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
    [MethodImpl(HotPath.Optimized)]
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
                // Whole blank words are skipped.
                index = NextExcept(words, index + 1, 0UL);
                if (index < 0)
                {
                    return count;
                }

                word = words[index];
            }

            var startBit = BitOperations.TrailingZeroCount(word);
            var start = (index << 6) + startBit;

            // The run ends at the first clear bit at or after its start: the lowest set bit of the complement.
            var clear = ~word & (ulong.MaxValue << startBit);
            if (clear == 0)
            {
                // Whole black words are skipped too.
                index = NextExcept(words, index + 1, ulong.MaxValue);
                if (index < 0)
                {
                    Add(ref runs, ref count, start, words.Length << 6);
                    return count;
                }

                clear = ~words[index];
            }

            var endBit = BitOperations.TrailingZeroCount(clear);
            Add(ref runs, ref count, start, (index << 6) + endBit);
            word = words[index] & (ulong.MaxValue << endBit);
        }
    }

    /// <summary>The first set pixel of a packed row and the end of its last run (its last set pixel + 1); false for a blank row.</summary>
    /// <remarks>What <see cref="Find"/>'s first and last edges would be, without finding the runs between them.</remarks>
    public static bool Extent(ReadOnlySpan<ulong> words, out int start, out int end)
    {
        var first = words.IndexOfAnyExcept(0UL);
        if (first < 0)
        {
            (start, end) = (0, 0);
            return false;
        }

        var last = words.LastIndexOfAnyExcept(0UL);
        start = (first << 6) + BitOperations.TrailingZeroCount(words[first]);
        end = (last << 6) + 64 - BitOperations.LeadingZeroCount(words[last]);
        return true;
    }

    /// <summary>The index of the first word at or after <paramref name="from"/> that is not <paramref name="value"/>, or -1.</summary>
    /// <remarks>A few words are looked at one by one first: most runs are short, and a vectorised search costs a call.</remarks>
    private static int NextExcept(ReadOnlySpan<ulong> words, int from, ulong value)
    {
        for (var end = Math.Min(words.Length, from + 4); from < end; from++)
        {
            if (words[from] != value)
            {
                return from;
            }
        }

        if (from >= words.Length)
        {
            return -1;
        }

        var next = words[from..].IndexOfAnyExcept(value);
        return next < 0 ? -1 : from + next;
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
