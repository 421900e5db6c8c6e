using System.Buffers.Binary;

namespace LaserEngrave.Wire.Zaber;

/// <summary>One 6-byte Zaber binary frame: device number, command number, signed 32-bit little-endian data.</summary>
public readonly record struct ZaberFrame(byte Device, ZaberCommand Command, int Data)
{
    public const int Length = 6;

    public static ZaberFrame Decode(ReadOnlySpan<byte> bytes)
    {
        if (bytes.Length < Length)
        {
            throw new ArgumentException($"a Zaber frame is {Length} bytes, got {bytes.Length}", nameof(bytes));
        }

        return new ZaberFrame(bytes[0], (ZaberCommand)bytes[1], BinaryPrimitives.ReadInt32LittleEndian(bytes[2..]));
    }

    public void Encode(Span<byte> destination)
    {
        destination[0] = Device;
        destination[1] = (byte)Command;
        BinaryPrimitives.WriteInt32LittleEndian(destination[2..], Data);
    }

    public byte[] ToBytes()
    {
        var bytes = new byte[Length];
        Encode(bytes);
        return bytes;
    }

    public override string ToString() => $"[{Device}, {(byte)Command} {Command}, {Data}]";
}
