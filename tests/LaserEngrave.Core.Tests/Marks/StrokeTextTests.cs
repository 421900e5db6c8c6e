using LaserEngrave.Core.Marks;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Tests.Marks;

/// <summary>The shipped single-stroke font and text laid out in it: height, alignment, line spacing, and the drawing it makes.</summary>
public class StrokeTextTests
{
    [Fact]
    public void Default_PrintableAscii_EveryCharacterHasAGlyph()
    {
        var font = HersheyFont.Default;

        Assert.All(Enumerable.Range(32, 95).Select(i => (char)i), c => Assert.True(font.Has(c), $"'{c}'"));
        Assert.Empty(font.Glyph(' ').Strokes);
    }

    [Fact]
    public void Glyph_CapitalL_IsTwoStraightStrokesOfOneLine()
    {
        // futural.jhf: "HYLFL[ RL[X[" – the stem from the cap top to the baseline, and the foot.
        var l = HersheyFont.Default.Glyph('L');

        Assert.Equal(2, l.Strokes.Count);
        Assert.Equal([new DrawingPoint(4, -12), new DrawingPoint(4, 9)], l.Strokes[0]);
        Assert.Equal(17, l.AdvanceUnits);
    }

    [Fact]
    public void Layout_Capitals_AreTheAskedHeightFromCapTopToBaseline()
    {
        var text = StrokeText.Layout("HEL", heightMm: 0.5);

        var (min, max) = text.InkBounds();
        Assert.Equal(0, min.Y, 9);
        Assert.Equal(0.5, max.Y, 9);
        Assert.Equal(0.5, text.HeightMm, 9);
    }

    [Fact]
    public void Layout_TwoLines_BaselinesAreTheLineSpacingApart()
    {
        var text = StrokeText.Layout("L\nL", heightMm: 1, lineSpacing: 2);

        Assert.Equal(3, text.HeightMm, 9);
        Assert.Equal(3, text.InkBounds().Max.Y, 9);
    }

    [Theory]
    [InlineData(TextAlign.Left, 0)]
    [InlineData(TextAlign.Center, 0.5)]
    [InlineData(TextAlign.Right, 1)]
    public void Layout_ShortLineUnderALongOne_SitsByTheAlignment(TextAlign align, double fraction)
    {
        var text = StrokeText.Layout("LLLL\nL", heightMm: 1, align: align);
        var lWidth = 17.0 / 21;

        var secondLineStem = text.Strokes[^2][0].X - (4.0 / 21);

        Assert.Equal(fraction * (text.WidthMm - lWidth), secondLineStem, 9);
        Assert.Equal(4 * lWidth, text.WidthMm, 9);
    }

    [Theory]
    [InlineData("S-001", 0.01, "text height")]
    [InlineData("S-001", 200, "text height")]
    [InlineData("", 1, "empty")]
    [InlineData("Ünïcode", 1, "no 'Ü'")]
    public void Layout_BadInput_IsRefusedInOneLine(string text, double height, string expected)
    {
        var ex = Assert.Throws<MarkException>(() => StrokeText.Layout(text, height));

        Assert.Contains(expected, ex.Message);
    }

    [Fact]
    public void WriteSvg_Strokes_ReadBackAsTheSameOpenPathsInMillimetres()
    {
        var text = StrokeText.Layout("S-001", heightMm: 0.4, align: TextAlign.Center);
        var path = Path.Combine(Path.GetTempPath(), $"stroke-text-{Guid.NewGuid():N}.svg");
        try
        {
            text.WriteSvg(path, dx: 1, dy: 2);

            var drawing = DrawingReader.Read(path);

            Assert.True(drawing.UnitsStated);
            Assert.Equal(text.Strokes.Count, drawing.Paths.Count);
            Assert.Equal(2, drawing.Paths.Count(p => p.Closed)); // the zeros end where they start
            var (min, max) = drawing.Bounds();
            var (inkMin, inkMax) = text.InkBounds();
            Assert.Equal(inkMin.X + 1, min.X, 5);
            Assert.Equal(inkMax.Y + 2, max.Y, 5);
        }
        finally
        {
            File.Delete(path);
        }
    }
}
