namespace LaserEngrave.Core.Imaging;

/// <summary>Error diffusion: each pixel's quantisation error is spread to neighbours not yet visited, by a fixed kernel.</summary>
internal sealed class ErrorDiffusionDitherer : Ditherer
{
    /// <summary>Floyd–Steinberg: 7/16 right; 3/16, 5/16, 1/16 below left, below, below right.</summary>
    public static readonly (int Dx, int Dy, float Weight)[] FloydSteinberg =
        [(1, 0, 7 / 16f), (-1, 1, 3 / 16f), (0, 1, 5 / 16f), (1, 1, 1 / 16f)];

    /// <summary>Atkinson: 1/8 each to two pixels right, three below and one two rows below; 2/8 of the error is dropped.</summary>
    public static readonly (int Dx, int Dy, float Weight)[] Atkinson =
        [(1, 0, 1 / 8f), (2, 0, 1 / 8f), (-1, 1, 1 / 8f), (0, 1, 1 / 8f), (1, 1, 1 / 8f), (0, 2, 1 / 8f)];

    private const int Margin = 2;

    private readonly (int Dx, int Dy, float Weight)[] _kernel;
    private readonly float[][] _errors;

    public ErrorDiffusionDitherer(int width, (int Dx, int Dy, float Weight)[] kernel)
    {
        _kernel = kernel;
        var rows = kernel.Max(k => k.Dy) + 1;
        _errors = new float[rows][];
        for (var i = 0; i < rows; i++)
        {
            _errors[i] = new float[width + (2 * Margin)];
        }
    }

    public override void DitherRow(int y, ReadOnlySpan<float> luminance, ReadOnlySpan<bool> transparent, Span<ulong> maskRow)
    {
        var current = _errors[0];
        for (var x = 0; x < luminance.Length; x++)
        {
            if (transparent[x])
            {
                continue;
            }

            var value = luminance[x] + current[x + Margin];
            var burn = value < 0.5f;
            if (burn)
            {
                maskRow[x >> 6] |= 1UL << (x & 63);
            }

            var error = burn ? value : value - 1f;
            foreach (var (dx, dy, weight) in _kernel)
            {
                _errors[dy][x + Margin + dx] += error * weight;
            }
        }

        // The next row's errors move up; the row that was current is cleared and becomes the furthest.
        Array.Clear(current);
        for (var i = 1; i < _errors.Length; i++)
        {
            _errors[i - 1] = _errors[i];
        }

        _errors[^1] = current;
    }
}
