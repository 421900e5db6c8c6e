using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Camera;

/// <summary>One grey camera image, 8 bits a pixel, row by row from the top left.</summary>
public sealed class CameraFrame
{
    public CameraFrame(int width, int height, byte[] pixels)
    {
        ArgumentOutOfRangeException.ThrowIfLessThan(width, 1);
        ArgumentOutOfRangeException.ThrowIfLessThan(height, 1);
        ArgumentNullException.ThrowIfNull(pixels);
        if (pixels.Length != width * height)
        {
            throw new ArgumentException($"a {width} x {height} frame has {width * height} pixels, got {pixels.Length}", nameof(pixels));
        }

        Width = width;
        Height = height;
        Pixels = pixels;
    }

    public int Width { get; }

    public int Height { get; }

    public byte[] Pixels { get; }

    public byte this[int x, int y] => Pixels[(y * Width) + x];

    /// <summary>The pixels as numbers, for the measurements.</summary>
    public double[] ToDoubles()
    {
        var values = new double[Pixels.Length];
        for (var i = 0; i < values.Length; i++)
        {
            values[i] = Pixels[i];
        }

        return values;
    }

    public void WritePng(Stream output) => PngWriter.WriteGray(output, Width, Height, Pixels);

    public byte[] ToPng()
    {
        using var stream = new MemoryStream();
        WritePng(stream);
        return stream.ToArray();
    }
}
