using System.Buffers.Binary;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Tests.Imaging;

/// <summary>Encodes a one-frame GIF with a real LZW encoder (growing codes, table resets), for decoder tests.</summary>
internal sealed record TestGif
{
    public int ScreenWidth { get; init; }

    public int ScreenHeight { get; init; }

    public int Left { get; init; }

    public int Top { get; init; }

    public int FrameWidth { get; init; }

    public int FrameHeight { get; init; }

    /// <summary>Frame indices, row-major top to bottom (the encoder interlaces them if asked).</summary>
    public required byte[] Indices { get; init; }

    public Rgba32[]? GlobalPalette { get; init; }

    public Rgba32[]? LocalPalette { get; init; }

    public int TransparentIndex { get; init; } = -1;

    public bool Interlaced { get; init; }

    public byte[] ToBytes()
    {
        using var file = new MemoryStream();
        file.Write("GIF89a"u8);
        var screen = new byte[7];
        BinaryPrimitives.WriteUInt16LittleEndian(screen, (ushort)ScreenWidth);
        BinaryPrimitives.WriteUInt16LittleEndian(screen.AsSpan(2), (ushort)ScreenHeight);
        if (GlobalPalette is not null)
        {
            screen[4] = (byte)(0x80 | SizeBits(GlobalPalette.Length));
        }

        file.Write(screen);
        if (GlobalPalette is not null)
        {
            WriteTable(file, GlobalPalette);
        }

        if (TransparentIndex >= 0)
        {
            file.Write([0x21, 0xF9, 4, 1, 0, 0, (byte)TransparentIndex, 0]);
        }

        // A comment extension, which the decoder must skip.
        file.Write([0x21, 0xFE, 3, (byte)'h', (byte)'i', (byte)'!', 0]);
        var descriptor = new byte[10];
        descriptor[0] = 0x2C;
        BinaryPrimitives.WriteUInt16LittleEndian(descriptor.AsSpan(1), (ushort)Left);
        BinaryPrimitives.WriteUInt16LittleEndian(descriptor.AsSpan(3), (ushort)Top);
        BinaryPrimitives.WriteUInt16LittleEndian(descriptor.AsSpan(5), (ushort)FrameWidth);
        BinaryPrimitives.WriteUInt16LittleEndian(descriptor.AsSpan(7), (ushort)FrameHeight);
        descriptor[9] = (byte)((LocalPalette is not null ? 0x80 | SizeBits(LocalPalette.Length) : 0) | (Interlaced ? 0x40 : 0));
        file.Write(descriptor);
        if (LocalPalette is not null)
        {
            WriteTable(file, LocalPalette);
        }

        var paletteLength = (LocalPalette ?? GlobalPalette)!.Length;
        var minCodeSize = Math.Max(2, SizeBits(paletteLength) + 1);
        file.WriteByte((byte)minCodeSize);
        var data = Lzw(StoredOrder(), minCodeSize);
        for (var at = 0; at < data.Length; at += 255)
        {
            var n = Math.Min(255, data.Length - at);
            file.WriteByte((byte)n);
            file.Write(data, at, n);
        }

        file.WriteByte(0);
        file.WriteByte(0x3B);
        return file.ToArray();
    }

    /// <summary>GIF LZW: codes LSB first, code size grows when the next code needs another bit, clear when the table is full.</summary>
    public static byte[] Lzw(byte[] indices, int minCodeSize)
    {
        var output = new List<byte>();
        var bitBuffer = 0L;
        var bitCount = 0;
        var clear = 1 << minCodeSize;
        var codeSize = minCodeSize + 1;
        var next = clear + 2;
        var table = new Dictionary<int, int>();

        void Emit(int code)
        {
            bitBuffer |= (long)code << bitCount;
            bitCount += codeSize;
            while (bitCount >= 8)
            {
                output.Add((byte)bitBuffer);
                bitBuffer >>= 8;
                bitCount -= 8;
            }
        }

        void Added()
        {
            if (next < 4096)
            {
                next++;
                if (next > 1 << codeSize && codeSize < 12)
                {
                    codeSize++;
                }
            }
        }

        Emit(clear);
        int prefix = indices[0];
        for (var i = 1; i < indices.Length; i++)
        {
            var key = (prefix << 8) | indices[i];
            if (table.TryGetValue(key, out var code))
            {
                prefix = code;
                continue;
            }

            Emit(prefix);
            if (next < 4096)
            {
                table[key] = next;
                Added();
            }
            else
            {
                Emit(clear);
                table.Clear();
                next = clear + 2;
                codeSize = minCodeSize + 1;
            }

            prefix = indices[i];
        }

        Emit(prefix);
        Added();
        Emit(clear + 1);
        if (bitCount > 0)
        {
            output.Add((byte)bitBuffer);
        }

        return [.. output];
    }

    private static int SizeBits(int length) => Math.Max(0, System.Numerics.BitOperations.Log2((uint)length) - 1);

    private static void WriteTable(Stream file, Rgba32[] palette)
    {
        foreach (var c in palette)
        {
            file.Write([c.R, c.G, c.B]);
        }
    }

    private byte[] StoredOrder()
    {
        if (!Interlaced)
        {
            return Indices;
        }

        var stored = new List<byte>();
        foreach (var (start, step) in new[] { (0, 8), (4, 8), (2, 4), (1, 2) })
        {
            for (var y = start; y < FrameHeight; y += step)
            {
                stored.AddRange(Indices.AsSpan(y * FrameWidth, FrameWidth).ToArray());
            }
        }

        return [.. stored];
    }
}
