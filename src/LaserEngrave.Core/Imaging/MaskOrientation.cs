namespace LaserEngrave.Core.Imaging;

/// <summary>Turns and mirrors a burn mask as <see cref="MaskOptions"/> says (mirror first, then quarter turns clockwise).</summary>
public static class MaskOrientation
{
    /// <summary>The mask as oriented by <paramref name="options"/>: <paramref name="mask"/> itself when it neither turns nor mirrors.</summary>
    public static BitMask Apply(BitMask mask, MaskOptions options)
    {
        ArgumentNullException.ThrowIfNull(mask);
        ArgumentNullException.ThrowIfNull(options);
        if (!options.Transforms)
        {
            return mask;
        }

        var turns = options.QuarterTurns & 3;
        var odd = (turns & 1) == 1;
        var result = new BitMask(odd ? mask.Height : mask.Width, odd ? mask.Width : mask.Height);
        var w = mask.Width;
        var h = mask.Height;
        for (var y = 0; y < h; y++)
        {
            var row = mask.ReadRow(y);
            var my = options.MirrorY ? h - 1 - y : y;
            for (var word = 0; word < row.Length; word++)
            {
                var bits = row[word];
                while (bits != 0)
                {
                    var x = (word << 6) + System.Numerics.BitOperations.TrailingZeroCount(bits);
                    bits &= bits - 1;
                    var mx = options.MirrorX ? w - 1 - x : x;

                    // Clockwise on the stage's picture (x right, y down): (x, y) goes to (h-1-y, x) for one quarter turn.
                    var (tx, ty) = turns switch
                    {
                        1 => (h - 1 - my, mx),
                        2 => (w - 1 - mx, h - 1 - my),
                        3 => (my, w - 1 - mx),
                        _ => (mx, my),
                    };
                    result[tx, ty] = true;
                }
            }
        }

        return result;
    }
}
