using System.Buffers.Binary;
using System.Numerics;

namespace LaserEngrave.Core.Imaging;

/// <summary>Turns 16-, 24- and 32-bit BMP pixels into RGBA through the file's channel masks.</summary>
internal sealed class BmpBitFields
{
    private readonly Channel _red;
    private readonly Channel _green;
    private readonly Channel _blue;
    private readonly Channel _alpha;
    private readonly int _bits;
    private readonly uint[]? _lookup16;

    public BmpBitFields(BmpHeader header)
    {
        _bits = header.BitsPerPixel;
        _red = new Channel(header.RedMask);
        _green = new Channel(header.GreenMask);
        _blue = new Channel(header.BlueMask);
        _alpha = new Channel(header.AlphaMask);
        if (_bits == 16)
        {
            // 65536 entries cost less than one 256 x 256 image's worth of per-pixel scaling.
            _lookup16 = new uint[1 << 16];
            for (var v = 0u; v < _lookup16.Length; v++)
            {
                _lookup16[v] = Pack(v);
            }
        }
    }

    /// <summary>Converts one stored row into 4 bytes per pixel.</summary>
    public void ConvertRow(ReadOnlySpan<byte> source, Span<byte> rgba, int width)
    {
        var output = System.Runtime.InteropServices.MemoryMarshal.Cast<byte, uint>(rgba[..(width * 4)]);
        switch (_bits)
        {
            case 24:
                for (var x = 0; x < width; x++)
                {
                    var p = source.Slice(x * 3, 3);
                    output[x] = ToLittleEndianRgba(p[2], p[1], p[0], 255);
                }

                break;
            case 16:
                for (var x = 0; x < width; x++)
                {
                    output[x] = _lookup16![BinaryPrimitives.ReadUInt16LittleEndian(source[(x * 2)..])];
                }

                break;
            default:
                for (var x = 0; x < width; x++)
                {
                    output[x] = Pack(BinaryPrimitives.ReadUInt32LittleEndian(source[(x * 4)..]));
                }

                break;
        }
    }

    /// <summary>The RGBA colour of a packed 24-bit BGR value as the RLE24 decoder stores it.</summary>
    public static uint PackBgr(byte b, byte g, byte r) => ToLittleEndianRgba(r, g, b, 255);

    private uint Pack(uint pixel) => ToLittleEndianRgba(
        _red.Extract(pixel),
        _green.Extract(pixel),
        _blue.Extract(pixel),
        _alpha.Bits == 0 ? (byte)255 : _alpha.Extract(pixel));

    private static uint ToLittleEndianRgba(byte r, byte g, byte b, byte a)
    {
        var value = r | ((uint)g << 8) | ((uint)b << 16) | ((uint)a << 24);
        return BitConverter.IsLittleEndian ? value : BinaryPrimitives.ReverseEndianness(value);
    }

    /// <summary>One colour channel: where its bits sit and how to scale them to 0..255.</summary>
    private readonly struct Channel
    {
        private readonly int _shift;
        private readonly ulong _max;

        public Channel(uint mask)
        {
            Bits = BitOperations.PopCount(mask);
            _shift = mask == 0 ? 0 : BitOperations.TrailingZeroCount(mask);
            _max = Bits == 0 ? 0 : (1UL << Bits) - 1;
        }

        public int Bits { get; }

        // A channel the masks leave out reads as 0; others scale with rounding so the full value is 255, not 248.
        public byte Extract(uint pixel)
        {
            if (Bits == 0)
            {
                return 0;
            }

            var v = (pixel >> _shift) & _max;
            return Bits == 8 ? (byte)v : (byte)(((v * 255) + (_max / 2)) / _max);
        }
    }
}
