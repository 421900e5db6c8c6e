using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Simulator.Burn;

/// <summary>Pulses landed on the job's grid, counted per sub-cell: <see cref="SubcellsPerPixel"/> x <see cref="SubcellsPerPixel"/> of them per pixel.</summary>
/// <remarks>
/// Sub-cell (i, j) of pixel (c, r) spans a quarter of the pixel's rounded width and height, so the map shows where within a
/// pixel the pulses piled up (a dwell at a run's start is a dark dot at the run's edge). Immutable.
/// </remarks>
public sealed class DoseMap
{
    /// <summary>Sub-cells per pixel along each axis.</summary>
    public const int SubcellsPerPixel = 4;

    private readonly int[] _counts;

    internal DoseMap(int widthPx, int heightPx, int[] counts)
    {
        WidthPx = widthPx;
        HeightPx = heightPx;
        _counts = counts;
        Max = counts.Length == 0 ? 0 : counts.Max();
    }

    public int WidthPx { get; }

    public int HeightPx { get; }

    /// <summary>Width of the map in sub-cells.</summary>
    public int Width => WidthPx * SubcellsPerPixel;

    /// <summary>Height of the map in sub-cells.</summary>
    public int Height => HeightPx * SubcellsPerPixel;

    /// <summary>Most pulses on one sub-cell.</summary>
    public int Max { get; }

    /// <summary>Pulses on sub-cell (<paramref name="x"/>, <paramref name="y"/>), counted from the grid's top left.</summary>
    public int this[int x, int y]
    {
        get
        {
            ArgumentOutOfRangeException.ThrowIfNegative(x);
            ArgumentOutOfRangeException.ThrowIfGreaterThanOrEqual(x, Width);
            ArgumentOutOfRangeException.ThrowIfNegative(y);
            ArgumentOutOfRangeException.ThrowIfGreaterThanOrEqual(y, Height);
            return _counts[((long)y * Width) + x];
        }
    }

    /// <summary>Pulses on pixel (<paramref name="column"/>, <paramref name="row"/>): the sum of its sub-cells.</summary>
    public int PulsesOnPixel(int column, int row)
    {
        var sum = 0;
        for (var j = 0; j < SubcellsPerPixel; j++)
        {
            for (var i = 0; i < SubcellsPerPixel; i++)
            {
                sum += this[(column * SubcellsPerPixel) + i, (row * SubcellsPerPixel) + j];
            }
        }

        return sum;
    }

    /// <summary>Writes the map as an 8-bit grey PNG, one pixel per sub-cell: white = no pulse, black = <see cref="Max"/> pulses, linear between.</summary>
    public void WritePng(Stream output)
    {
        var grey = new byte[_counts.Length];
        for (var i = 0; i < grey.Length; i++)
        {
            grey[i] = Max == 0 ? (byte)255 : (byte)Math.Round(255.0 - (255.0 * _counts[i] / Max), MidpointRounding.AwayFromZero);
        }

        PngWriter.WriteGray(output, Width, Height, grey);
    }

    /// <inheritdoc cref="WritePng(Stream)"/>
    public void WritePng(string path)
    {
        using var file = File.Create(path);
        WritePng(file);
    }
}
