using LaserEngrave.Core.Marks;

namespace LaserEngrave.Core.Tests.Marks;

/// <summary>QR and Data Matrix made from a text, drawn into a burn mask, and read back by ZXing.</summary>
public class CodeSymbolTests
{
    [Theory]
    [InlineData(CodeKind.DataMatrix, "S-001", null)]
    [InlineData(CodeKind.DataMatrix, "wafer 17/B, 2026-11-27", null)]
    [InlineData(CodeKind.Qr, "S-001", 'L')]
    [InlineData(CodeKind.Qr, "S-001", 'H')]
    [InlineData(CodeKind.Qr, "https://lab.example/samples/S-042?run=7", 'M')]
    public void Render_AnyText_DecodesBackToTheText(CodeKind kind, string text, char? ecc)
    {
        var symbol = CodeSymbol.Encode(kind, text, ecc);
        var raster = CodeRaster.Render(symbol, moduleUm: 100, quietModules: 2, spotDiameterUm: 20);

        Assert.Equal(text, CodeDecoder.Decode(raster.Mask, kind));
    }

    [Fact]
    public void Encode_DataMatrixOfASampleId_IsTwelveModulesSquare()
    {
        var symbol = CodeSymbol.Encode(CodeKind.DataMatrix, "S-001");

        Assert.Equal((12, 12), (symbol.Modules.Width, symbol.Modules.Height));
    }

    [Fact]
    public void Encode_QrAtHigherCorrection_IsNeverSmaller()
    {
        var low = CodeSymbol.Encode(CodeKind.Qr, "sample 0123456789 abcdef", 'L');
        var high = CodeSymbol.Encode(CodeKind.Qr, "sample 0123456789 abcdef", 'H');

        Assert.True(high.Size > low.Size, $"H {high.Size} modules, L {low.Size}");
    }

    [Fact]
    public void Render_ModuleAndQuietZone_SizesTheMaskInWholeModules()
    {
        var symbol = CodeSymbol.Encode(CodeKind.DataMatrix, "S-001");

        var raster = CodeRaster.Render(symbol, moduleUm: 166.6667, quietModules: 1, spotDiameterUm: 20);

        Assert.Equal(9, raster.PixelsPerModule);
        Assert.Equal(14 * 9, raster.Mask.Width);
        Assert.True(raster.PitchUm <= 20);
        Assert.Equal(2.0, raster.SymbolMm, 3);
        Assert.False(raster.Mask[8, 8], "the quiet zone is white");
    }

    [Fact]
    public void Render_ModuleSmallerThanTheSpot_IsRefusedNamingTheSpot()
    {
        var symbol = CodeSymbol.Encode(CodeKind.DataMatrix, "S-001");

        var ex = Assert.Throws<MarkException>(() => CodeRaster.Render(symbol, moduleUm: 15, quietModules: 1, spotDiameterUm: 20));

        Assert.Contains("smaller than the spot's 20 µm diameter", ex.Message);
    }

    [Theory]
    [InlineData(CodeKind.Qr, "", null, "empty")]
    [InlineData(CodeKind.Qr, "x", 'X', "not L, M, Q or H")]
    [InlineData(CodeKind.DataMatrix, "x", 'H', "for QR codes")]
    [InlineData(CodeKind.DataMatrix, "\u4e2d", null, "Latin-1")]
    public void Encode_BadInput_IsRefusedInOneLine(CodeKind kind, string text, char? ecc, string expected)
    {
        var ex = Assert.Throws<MarkException>(() => CodeSymbol.Encode(kind, text, ecc));

        Assert.Contains(expected, ex.Message);
    }

    [Fact]
    public void Encode_TextTooLongForAQrCode_IsRefused()
    {
        var ex = Assert.Throws<MarkException>(() => CodeSymbol.Encode(CodeKind.Qr, new string('x', 501), 'H'));

        Assert.Contains("more than the 500", ex.Message);
    }

    [Fact]
    public void Decode_BlankPicture_IsNull()
    {
        Assert.Null(CodeDecoder.Decode(new Core.Imaging.BitMask(50, 50), CodeKind.DataMatrix));
    }
}
