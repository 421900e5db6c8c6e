using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Marks;

namespace LaserEngrave.Core.Tests.Jobs;

/// <summary>Marks made into a job of layers: the array, each copy's number and place, and the layers the run engine burns.</summary>
public sealed class MarkLayoutTests : IDisposable
{
    private readonly string _folder = Directory.CreateTempSubdirectory("mark-layout-").FullName;

    public void Dispose() => Directory.Delete(_folder, recursive: true);

    private static readonly MarkContext Context = new(0, null, DateTimeOffset.UnixEpoch, "test");

    private static MarkSpec TenIds => new()
    {
        Text = "S-{n:000}",
        Code = CodeKind.DataMatrix,
        SizeMm = 2,
        Copies = 10,
        Columns = 5,
        PitchXMm = 4,
        PitchYMm = 4,
        Origin = new OriginMm(10, 10),
    };

    [Fact]
    public void Make_TenCopiesOnAGrid_EachHasItsOwnNumberAndPlace()
    {
        var layout = MarkLayout.Make(TenIds, 1, Context, MachineProfile.Default, _folder);

        var codes = layout.Marks.Where(m => m.Kind == "datamatrix").ToList();
        Assert.Equal(Enumerable.Range(1, 10).Select(n => $"S-{n:000}"), codes.Select(m => m.Text));
        Assert.Equal(20, layout.Layers.Count);
        var quiet = 2.0 / 12;
        Assert.Equal((10 + quiet, 10 + quiet), (codes[0].XMm, codes[0].YMm));
        Assert.Equal(14 + quiet, codes[1].XMm, 9);
        Assert.Equal((10 + quiet, 14 + quiet), (codes[5].XMm, codes[5].YMm));
        Assert.All(codes, c => Assert.Equal(2, c.WidthMm, 9));
        var texts = layout.Marks.Where(m => m.Kind == "text").ToList();
        Assert.All(texts.Zip(codes), p => Assert.True(p.First.YMm > p.Second.YMm + p.Second.HeightMm, $"{p.First.Text} is beneath its code"));
        Assert.All(texts.Zip(codes), p => Assert.Equal(p.Second.XMm + (p.Second.WidthMm / 2), p.First.XMm + (p.First.WidthMm / 2), 6));
    }

    [Fact]
    public void Make_CodeLayers_PrepareIntoTheSameMaskAndTheirNamesCarryTheText()
    {
        var layout = MarkLayout.Make(TenIds with { Copies = 2, Columns = null }, 41, Context, MachineProfile.Default, _folder);
        var job = JobFile.Load(layout.Save(_folder, Path.Combine(_folder, MarkCounter.FileName)));

        var prepared = LayeredJob.Prepare(job, MachineProfile.Default);

        Assert.Equal(["Data Matrix \"S-041\"", "text \"S-041\"", "Data Matrix \"S-042\"", "text \"S-042\""], prepared.Layers.Select(l => l.Layer.Name));
        Assert.True(prepared.Layers[0].Image!.Mask.ContentEquals(layout.Codes[0].Mask), "the BMP reads back as the drawn code");
        Assert.Equal("S-041", CodeDecoder.Decode(prepared.Layers[0].Image!.Mask, CodeKind.DataMatrix));
        Assert.NotNull(prepared.Layers[1].Drawing);
        Assert.True(prepared.FitsTravel);
    }

    [Fact]
    public void Make_TextAlone_IsOneDrawingLayerAtTheOrigin()
    {
        var layout = MarkLayout.Make(new MarkSpec { Text = "{profile}", TextHeightMm = 1, Align = TextAlign.Left }, 1, Context, MachineProfile.Default, _folder);

        var mark = Assert.Single(layout.Marks);
        Assert.Equal(("test", "text"), (mark.Text, mark.Kind));
        Assert.Equal(LayerMode.Outline, Assert.Single(layout.Layers).Mode);
        Assert.InRange(mark.YMm, 10, 10.01);
    }

    [Theory]
    [InlineData(null, null, "one of the two")]
    [InlineData(1.0, 100.0, "one of the two")]
    public void Make_CodeWithoutOrWithBothSizes_IsRefused(double? sizeMm, double? moduleUm, string expected)
    {
        var ex = Assert.Throws<MarkException>(() => MarkLayout.Make(TenIds with { SizeMm = sizeMm, ModuleUm = moduleUm }, 1, Context, MachineProfile.Default, _folder));

        Assert.Contains(expected, ex.Message);
    }

    [Fact]
    public void Make_CodeTooSmallForTheSpot_IsRefusedBeforeAnyFileIsWritten()
    {
        var folder = Path.Combine(_folder, "small");

        var ex = Assert.Throws<MarkException>(() => MarkLayout.Make(TenIds with { SizeMm = 0.2 }, 1, Context, MachineProfile.Default, folder));

        Assert.Contains("smaller than the spot", ex.Message);
        Assert.False(Directory.Exists(folder));
    }

    [Theory]
    [InlineData(0, null, "copies 0")]
    [InlineData(401, null, "copies 401")]
    [InlineData(10, 0, "columns 0 must be 1..")]
    public void Make_BadArray_IsRefused(int copies, int? columns, string expected)
    {
        var ex = Assert.Throws<MarkException>(() => MarkLayout.Make(TenIds with { Copies = copies, Columns = columns }, 1, Context, MachineProfile.Default, _folder));

        Assert.Contains(expected, ex.Message);
    }

    [Fact]
    public void Make_MoreColumnsThanCopies_OneRowOfTheCopies()
    {
        var layout = MarkLayout.Make(TenIds with { Copies = 1, Columns = 5 }, 1, Context, MachineProfile.Default, _folder);

        Assert.Equal([1], layout.Marks.Select(m => m.Number).Distinct());
    }
}
