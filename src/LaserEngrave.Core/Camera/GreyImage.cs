namespace LaserEngrave.Core.Camera;

/// <summary>A grey image as numbers, for measuring: crops, bilinear samples and the spread of its brightness.</summary>
public sealed class GreyImage
{
    public GreyImage(int width, int height, double[] values)
    {
        ArgumentNullException.ThrowIfNull(values);
        if (values.Length != width * height)
        {
            throw new ArgumentException($"a {width} x {height} image has {width * height} values, got {values.Length}", nameof(values));
        }

        Width = width;
        Height = height;
        Values = values;
    }

    public int Width { get; }

    public int Height { get; }

    public double[] Values { get; }

    public double this[int x, int y] => Values[(y * Width) + x];

    public static GreyImage Of(CameraFrame frame)
    {
        ArgumentNullException.ThrowIfNull(frame);
        return new GreyImage(frame.Width, frame.Height, frame.ToDoubles());
    }

    /// <summary>The part from (<paramref name="x"/>, <paramref name="y"/>), <paramref name="width"/> x <paramref name="height"/> pixels, all inside the image.</summary>
    public GreyImage Crop(int x, int y, int width, int height)
    {
        if (x < 0 || y < 0 || width < 1 || height < 1 || x + width > Width || y + height > Height)
        {
            throw new ArgumentOutOfRangeException(nameof(x), $"the crop {x},{y} {width} x {height} is not inside the {Width} x {Height} image");
        }

        var values = new double[width * height];
        for (var row = 0; row < height; row++)
        {
            Array.Copy(Values, ((y + row) * Width) + x, values, row * width, width);
        }

        return new GreyImage(width, height, values);
    }

    /// <summary>Bilinear value at (<paramref name="x"/>, <paramref name="y"/>); NaN outside the pixel centres' hull.</summary>
    public double Sample(double x, double y)
    {
        if (!(x >= 0 && y >= 0 && x <= Width - 1 && y <= Height - 1))
        {
            return double.NaN;
        }

        var ix = Math.Min((int)x, Width - 2);
        var iy = Math.Min((int)y, Height - 2);
        var fx = x - ix;
        var fy = y - iy;
        var i = (iy * Width) + ix;
        var top = Values[i] + ((Values[i + 1] - Values[i]) * fx);
        var bottom = Values[i + Width] + ((Values[i + Width + 1] - Values[i + Width]) * fx);
        return top + ((bottom - top) * fy);
    }

    /// <summary>Standard deviation of the brightness, grey levels.</summary>
    public double Spread()
    {
        var mean = Values.Average();
        return Math.Sqrt(Values.Sum(v => (v - mean) * (v - mean)) / Values.Length);
    }
}
