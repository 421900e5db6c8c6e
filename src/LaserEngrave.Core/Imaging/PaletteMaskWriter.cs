using System.Buffers.Binary;

namespace LaserEngrave.Core.Imaging;

/// <summary>
/// Maps rows of packed palette indices straight to mask words through a per-index burn table, never expanding to colours.
/// </summary>
/// <remarks>
/// The palette decides what burns: index 0 burns if colour 0 is dark, whatever the index. For 1-bit rows this works
/// on 64 pixels at a time: the file's leftmost pixel is a byte's most significant bit and the mask's leftmost pixel is
/// a word's least significant bit, so the bits of each byte are reversed (within the word, by swapping halves) and the
/// two palette entries pick between the bits, their complement, all zeros or all ones.
/// </remarks>
internal sealed class PaletteMaskWriter
{
    private static readonly byte[] ReversedBits = BuildReversedBits();

    private readonly int _bits;
    private readonly ulong _whereOne;
    private readonly ulong _whereZero;
    private readonly ushort[]? _byteToBits;

    private PaletteMaskWriter(int bits, bool[] burns)
    {
        _bits = bits;
        if (bits == 1)
        {
            _whereZero = burns[0] ? ulong.MaxValue : 0;
            _whereOne = burns[1] ? ulong.MaxValue : 0;
            return;
        }

        // Each byte holds 8 / bits pixels; the table gives their burn bits, leftmost pixel in bit 0.
        var pixelsPerByte = 8 / bits;
        _byteToBits = new ushort[256];
        for (var b = 0; b < 256; b++)
        {
            var value = 0;
            for (var p = 0; p < pixelsPerByte; p++)
            {
                var index = (b >> (8 - ((p + 1) * bits))) & ((1 << bits) - 1);
                value |= burns[index] ? 1 << p : 0;
            }

            _byteToBits[b] = (ushort)value;
        }
    }

    /// <summary>A writer for this palette and these options, or null when dithering a palette with greys needs the general path.</summary>
    public static PaletteMaskWriter? TryCreate(ReadOnlySpan<Rgba32> palette, int bits, MaskOptions options)
    {
        // With only black, white and fully transparent entries, every dither gives exactly what mid-grey thresholding gives.
        var dithered = options.Dither != DitherMethod.None;
        if (dithered)
        {
            foreach (var colour in palette)
            {
                if (colour.A != 0 && colour.Luminance is not (0.0 or 1.0))
                {
                    return null;
                }
            }
        }

        // Indices past the palette never occur (decoders refuse them); they are given "no burn" only to fill the table.
        var burns = new bool[1 << bits];
        for (var i = 0; i < palette.Length && i < burns.Length; i++)
        {
            var colour = palette[i];
            var dark = dithered ? colour.Luminance < 0.5 : options.IsDark(colour);
            burns[i] = colour.A != 0 && (dark ^ options.Invert);
        }

        return new PaletteMaskWriter(bits, burns);
    }

    /// <summary>Writes the mask words of one row from its packed indices (leftmost pixel in a byte's high bits).</summary>
    public void Write(ReadOnlySpan<byte> packed, Span<ulong> maskRow, int width)
    {
        if (_bits == 1)
        {
            WriteOneBit(packed, maskRow, width);
        }
        else
        {
            WriteMultiBit(packed, maskRow, width);
        }

        var tail = width & 63;
        if (tail != 0)
        {
            maskRow[(width - 1) >> 6] &= (1UL << tail) - 1;
        }
    }

    /// <summary>Reverses the bit order inside each byte of a word: swap neighbours, then pairs, then nibbles.</summary>
    internal static ulong ReverseBitsInEachByte(ulong v)
    {
        v = ((v >> 1) & 0x5555555555555555UL) | ((v & 0x5555555555555555UL) << 1);
        v = ((v >> 2) & 0x3333333333333333UL) | ((v & 0x3333333333333333UL) << 2);
        return ((v >> 4) & 0x0F0F0F0F0F0F0F0FUL) | ((v & 0x0F0F0F0F0F0F0F0FUL) << 4);
    }

    private void WriteOneBit(ReadOnlySpan<byte> packed, Span<ulong> maskRow, int width)
    {
        var rowBytes = (width + 7) >> 3;
        var whole = rowBytes >> 3;
        for (var k = 0; k < whole; k++)
        {
            var bits = ReverseBitsInEachByte(BinaryPrimitives.ReadUInt64LittleEndian(packed[(k << 3)..]));
            maskRow[k] = (bits & _whereOne) | (~bits & _whereZero);
        }

        if ((rowBytes & 7) != 0)
        {
            ulong bits = 0;
            var tail = packed[(whole << 3)..rowBytes];
            for (var j = 0; j < tail.Length; j++)
            {
                bits |= (ulong)ReversedBits[tail[j]] << (j << 3);
            }

            maskRow[whole] = (bits & _whereOne) | (~bits & _whereZero);
        }
    }

    private void WriteMultiBit(ReadOnlySpan<byte> packed, Span<ulong> maskRow, int width)
    {
        var table = _byteToBits!;
        var pixelsPerByte = 8 / _bits;
        var rowBytes = (int)ImageLimits.IndexedStride(width, _bits);
        ulong word = 0;
        int shift = 0, k = 0;
        foreach (var b in packed[..rowBytes])
        {
            word |= (ulong)table[b] << shift;
            shift += pixelsPerByte;
            if (shift == 64)
            {
                maskRow[k++] = word;
                word = 0;
                shift = 0;
            }
        }

        if (shift != 0)
        {
            maskRow[k] = word;
        }
    }

    private static byte[] BuildReversedBits()
    {
        var table = new byte[256];
        for (var b = 0; b < 256; b++)
        {
            table[b] = (byte)ReverseBitsInEachByte((ulong)b);
        }

        return table;
    }
}
