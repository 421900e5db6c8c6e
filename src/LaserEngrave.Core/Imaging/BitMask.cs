using System.Numerics;

namespace LaserEngrave.Core.Imaging;

/// <summary>A 1-bit image packed 64 pixels to a word, row by row; a set bit means "burn".</summary>
/// <remarks>
/// Pixel x of row y is bit (x &amp; 63) of word (x &gt;&gt; 6) of that row: the least significant bit is the leftmost pixel.
/// Bits past the width in a row's last word are always zero, so whole-word operations never see phantom pixels.
/// </remarks>
public sealed class BitMask
{
    /// <summary>Widest and tallest mask accepted (pixels per side); guards allocations sized by a file header.</summary>
    public const int MaxSide = 1 << 20;

    /// <summary>Largest mask accepted, in pixels (4 gigapixels = 512 MB packed).</summary>
    public const long MaxPixels = 1L << 32;

    private readonly ulong[] _words;

    public BitMask(int width, int height)
    {
        if (width <= 0 || height <= 0 || width > MaxSide || height > MaxSide || (long)width * height > MaxPixels)
        {
            throw new ArgumentOutOfRangeException(nameof(width), $"a mask of {width} x {height} pixels is outside 1..{MaxSide} per side");
        }

        Width = width;
        Height = height;
        WordsPerRow = (width + 63) >> 6;
        _words = new ulong[(long)WordsPerRow * height];
    }

    public int Width { get; }

    public int Height { get; }

    public int WordsPerRow { get; }

    /// <summary>Mask of the valid bits in a row's last word.</summary>
    public ulong LastWordMask => (Width & 63) == 0 ? ulong.MaxValue : (1UL << (Width & 63)) - 1;

    public bool this[int x, int y]
    {
        get => (Row(y)[x >> 6] >> (x & 63) & 1) != 0;
        set
        {
            ref var word = ref Row(y)[x >> 6];
            var bit = 1UL << (x & 63);
            word = value ? word | bit : word & ~bit;
        }
    }

    /// <summary>The packed words of row <paramref name="y"/>.</summary>
    public Span<ulong> Row(int y)
    {
        if ((uint)y >= (uint)Height)
        {
            throw new ArgumentOutOfRangeException(nameof(y));
        }

        return _words.AsSpan(y * WordsPerRow, WordsPerRow);
    }

    /// <summary>The packed words of row <paramref name="y"/>, read-only.</summary>
    public ReadOnlySpan<ulong> ReadRow(int y) => Row(y);

    /// <summary>Number of set (burn) pixels.</summary>
    public long CountSet()
    {
        long n = 0;
        foreach (var w in _words)
        {
            n += BitOperations.PopCount(w);
        }

        return n;
    }

    /// <summary>Number of set pixels in row <paramref name="y"/>.</summary>
    public int CountSet(int y)
    {
        var n = 0;
        foreach (var w in ReadRow(y))
        {
            n += BitOperations.PopCount(w);
        }

        return n;
    }

    /// <summary>Clears the padding bits past the width; call after filling rows word by word.</summary>
    public void ClearPadding()
    {
        var last = LastWordMask;
        if (last == ulong.MaxValue)
        {
            return;
        }

        for (var y = 0; y < Height; y++)
        {
            Row(y)[WordsPerRow - 1] &= last;
        }
    }

    public bool ContentEquals(BitMask other)
    {
        ArgumentNullException.ThrowIfNull(other);
        return other.Width == Width && other.Height == Height && _words.AsSpan().SequenceEqual(other._words);
    }

    public BitMask Clone()
    {
        var copy = new BitMask(Width, Height);
        _words.CopyTo(copy._words, 0);
        return copy;
    }
}
