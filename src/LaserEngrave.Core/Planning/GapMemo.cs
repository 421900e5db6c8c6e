namespace LaserEngrave.Core.Planning;

/// <summary>
/// Remembers a pure function of a length in whole microsteps (a gap's, a travel's): a large plan asks the same question
/// of millions of gaps that have only thousands of lengths, and the answer takes a search to compute.
/// </summary>
/// <remarks>
/// Lengths are kept in pages of 1024, made when first needed; lengths past <see cref="MaxLength"/> are computed every
/// time. Safe to share between threads without a lock: a value is written before its flag (a release), read after it
/// (an acquire), and two threads that compute the same length write the same bits.
/// </remarks>
internal sealed class GapMemo<T>(Func<long, T> compute)
{
    /// <summary>Lengths below this are remembered (1.6 m of a 0.1 µm microstep).</summary>
    public const long MaxLength = 1L << 24;

    private const int PageBits = 10;
    private const int PageSize = 1 << PageBits;

    private Page?[]? _pages;

    /// <summary>The function's value at <paramref name="length"/>, computed once.</summary>
    public T Get(long length)
    {
        if ((ulong)length >= MaxLength)
        {
            return compute(length);
        }

        var page = _pages?[length >> PageBits];
        var i = (int)(length & (PageSize - 1));
        if (page is not null && Volatile.Read(ref page.Known[i]))
        {
            return page.Values[i];
        }

        return Fill(length, i);
    }

    private T Fill(long length, int i)
    {
        // Whichever thread installs a page (or the table) first wins; the others use it.
        if (Volatile.Read(ref _pages) is null)
        {
            Interlocked.CompareExchange(ref _pages, new Page?[MaxLength >> PageBits], null);
        }

        var pages = _pages!;
        ref var slot = ref pages[length >> PageBits];
        if (Volatile.Read(ref slot) is null)
        {
            Interlocked.CompareExchange(ref slot, new Page(), null);
        }

        var page = slot!;
        var value = compute(length);
        page.Values[i] = value;
        Volatile.Write(ref page.Known[i], true);
        return value;
    }

    private sealed class Page
    {
        public readonly T[] Values = new T[PageSize];
        public readonly bool[] Known = new bool[PageSize];
    }
}
