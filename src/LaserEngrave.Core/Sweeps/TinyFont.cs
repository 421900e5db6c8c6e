namespace LaserEngrave.Core.Sweeps;

/// <summary>A 3 x 5 pixel font of digits, '.', and '-', for the labels a sweep burns beside its rows and columns.</summary>
public static class TinyFont
{
    /// <summary>Glyph width, pixels; a character takes one more (the space after it).</summary>
    public const int GlyphWidth = 3;

    public const int GlyphHeight = 5;

    // Each glyph: five rows of three bits, the leftmost pixel the highest bit.
    private static readonly Dictionary<char, int[]> Glyphs = new()
    {
        ['0'] = [0b111, 0b101, 0b101, 0b101, 0b111],
        ['1'] = [0b010, 0b110, 0b010, 0b010, 0b111],
        ['2'] = [0b111, 0b001, 0b111, 0b100, 0b111],
        ['3'] = [0b111, 0b001, 0b111, 0b001, 0b111],
        ['4'] = [0b101, 0b101, 0b111, 0b001, 0b001],
        ['5'] = [0b111, 0b100, 0b111, 0b001, 0b111],
        ['6'] = [0b111, 0b100, 0b111, 0b101, 0b111],
        ['7'] = [0b111, 0b001, 0b010, 0b010, 0b010],
        ['8'] = [0b111, 0b101, 0b111, 0b101, 0b111],
        ['9'] = [0b111, 0b101, 0b111, 0b001, 0b111],
        ['.'] = [0b000, 0b000, 0b000, 0b000, 0b010],
        ['-'] = [0b000, 0b000, 0b111, 0b000, 0b000],
    };

    /// <summary>Width of <paramref name="text"/> in pixels, without the space after the last character.</summary>
    public static int Width(string text) => string.IsNullOrEmpty(text) ? 0 : (text.Length * (GlyphWidth + 1)) - 1;

    /// <summary>Whether every character of <paramref name="text"/> has a glyph.</summary>
    public static bool CanDraw(string text) => text.All(Glyphs.ContainsKey);

    /// <summary>Sets the pixels of <paramref name="text"/> with its top-left corner at (<paramref name="x"/>, <paramref name="y"/>); pixels off the mask are left out.</summary>
    public static void Draw(Imaging.BitMask mask, string text, int x, int y)
    {
        ArgumentNullException.ThrowIfNull(mask);
        ArgumentNullException.ThrowIfNull(text);
        for (var i = 0; i < text.Length; i++)
        {
            if (!Glyphs.TryGetValue(text[i], out var rows))
            {
                throw new ArgumentException($"'{text[i]}' has no glyph in the tiny font", nameof(text));
            }

            for (var row = 0; row < GlyphHeight; row++)
            {
                for (var column = 0; column < GlyphWidth; column++)
                {
                    var px = x + (i * (GlyphWidth + 1)) + column;
                    var py = y + row;
                    if ((rows[row] & (1 << (GlyphWidth - 1 - column))) != 0 && px >= 0 && py >= 0 && px < mask.Width && py < mask.Height)
                    {
                        mask[px, py] = true;
                    }
                }
            }
        }
    }
}
