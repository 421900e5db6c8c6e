using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Preview;

/// <summary>An RGBA pixel buffer with the few drawing operations the previews need.</summary>
/// <remarks>Drawn by hand because no drawing library (SkiaSharp, ImageSharp) is on this machine's package source.</remarks>
public sealed class RgbaCanvas
{
    private readonly byte[] _pixels;

    public RgbaCanvas(int width, int height, Rgba background)
    {
        ArgumentOutOfRangeException.ThrowIfLessThan(width, 1);
        ArgumentOutOfRangeException.ThrowIfLessThan(height, 1);
        Width = width;
        Height = height;
        _pixels = new byte[(long)width * height * 4];
        FillRect(0, 0, width - 1, height - 1, background);
    }

    public int Width { get; }

    public int Height { get; }

    /// <summary>The pixels, 4 bytes each (R, G, B, A), rows top to bottom.</summary>
    public ReadOnlySpan<byte> Pixels => _pixels;

    public Rgba this[int x, int y]
    {
        get
        {
            var i = Index(x, y);
            return new Rgba(_pixels[i], _pixels[i + 1], _pixels[i + 2], _pixels[i + 3]);
        }
    }

    /// <summary>Sets one pixel; pixels outside the canvas are ignored.</summary>
    public void Set(int x, int y, Rgba colour)
    {
        if ((uint)x >= (uint)Width || (uint)y >= (uint)Height)
        {
            return;
        }

        var i = Index(x, y);
        _pixels[i] = colour.R;
        _pixels[i + 1] = colour.G;
        _pixels[i + 2] = colour.B;
        _pixels[i + 3] = colour.A;
    }

    /// <summary>Fills the rectangle between two corners, both included, clipped to the canvas.</summary>
    public void FillRect(int x0, int y0, int x1, int y1, Rgba colour)
    {
        int left = Math.Max(0, Math.Min(x0, x1)), right = Math.Min(Width - 1, Math.Max(x0, x1));
        int top = Math.Max(0, Math.Min(y0, y1)), bottom = Math.Min(Height - 1, Math.Max(y0, y1));
        for (var y = top; y <= bottom; y++)
        {
            for (var x = left; x <= right; x++)
            {
                Set(x, y, colour);
            }
        }
    }

    /// <summary>Draws the one-pixel border of the rectangle between two corners.</summary>
    public void DrawRect(int x0, int y0, int x1, int y1, Rgba colour)
    {
        DrawLine(x0, y0, x1, y0, colour);
        DrawLine(x1, y0, x1, y1, colour);
        DrawLine(x1, y1, x0, y1, colour);
        DrawLine(x0, y1, x0, y0, colour);
    }

    /// <summary>Draws a one-pixel line, both ends included (Bresenham).</summary>
    public void DrawLine(int x0, int y0, int x1, int y1, Rgba colour)
    {
        int dx = Math.Abs(x1 - x0), dy = -Math.Abs(y1 - y0);
        int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
        var error = dx + dy;
        while (true)
        {
            Set(x0, y0, colour);
            if (x0 == x1 && y0 == y1)
            {
                return;
            }

            var doubled = 2 * error;
            if (doubled >= dy)
            {
                error += dy;
                x0 += sx;
            }

            if (doubled <= dx)
            {
                error += dx;
                y0 += sy;
            }
        }
    }

    public void FillCircle(int cx, int cy, int radius, Rgba colour)
    {
        for (var y = -radius; y <= radius; y++)
        {
            for (var x = -radius; x <= radius; x++)
            {
                if ((x * x) + (y * y) <= radius * radius)
                {
                    Set(cx + x, cy + y, colour);
                }
            }
        }
    }

    public void WritePng(Stream output) => PngWriter.WriteRgba(output, Width, Height, _pixels);

    private long Index(int x, int y)
    {
        if ((uint)x >= (uint)Width || (uint)y >= (uint)Height)
        {
            throw new ArgumentOutOfRangeException(nameof(x), $"({x}, {y}) is outside the {Width} x {Height} canvas");
        }

        return (((long)y * Width) + x) * 4;
    }
}
