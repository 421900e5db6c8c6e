using LaserEngrave.Core.Marks;

namespace LaserEngrave.Core.Tests.Marks;

/// <summary>Text in a system font through SkiaSharp (DejaVu Sans is installed on the build machines with fontconfig).</summary>
public class SystemFontTextTests
{
    [Fact]
    public void Render_InstalledFont_FillsCapitalsOfTheAskedHeight()
    {
        var mask = SystemFontText.Render("HI", "DejaVu Sans", heightMm: 1, pitchUm: 10);

        var rows = Enumerable.Range(0, mask.Height).Where(y => mask.CountSet(y) > 0).ToList();
        Assert.InRange(rows[^1] - rows[0] + 1, 98, 102);
        Assert.True(mask.CountSet() > 1000);
    }

    [Fact]
    public void Render_FontNotInstalled_IsRefusedNamingIt()
    {
        var ex = Assert.Throws<MarkException>(() => SystemFontText.Render("HI", "No Such Font 123", heightMm: 1, pitchUm: 10));

        Assert.Contains("\"No Such Font 123\" is not installed", ex.Message);
    }
}
