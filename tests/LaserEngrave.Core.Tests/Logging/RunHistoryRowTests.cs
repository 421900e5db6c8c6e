using System.Text.Json;
using LaserEngrave.Core.Logging;

namespace LaserEngrave.Core.Tests.Logging;

/// <summary>The run history as a lab notebook's table: one row a run, exported as CSV for a spreadsheet and as JSON.</summary>
public sealed class RunHistoryRowTests : IDisposable
{
    private readonly TestRuns _runs = new();

    public void Dispose() => _runs.Dispose();

    private RunHistoryRow Row(string? sample = "S-17") => RunHistoryRow.From("/logs/run.json", _runs.FailedRecord(sample));

    [Fact]
    public void From_LoggedRun_TheNotebooksFields()
    {
        var row = Row();

        Assert.Equal(("S-17", "qr-code.bmp", "image"), (row.SampleId, row.Source, row.Kind));
        Assert.Equal((10.5, 7.25), (row.OriginXMm, row.OriginYMm));
        Assert.Equal((0.8, 1500.0), (row.BurnSpeedMmPerS, row.LaserFrequencyHz));
        Assert.Equal((61.5, 70.3), (row.ActualSeconds, row.EstimatedSeconds));
        Assert.Equal(Core.Jobs.RunOutcome.Failed, row.Outcome);
        Assert.StartsWith("0.8 mm/s · 1500 Hz · ", row.ProcessText, StringComparison.Ordinal);
    }

    [Fact]
    public void From_Drawing_KindDrawingAndNoPitch()
    {
        var path = TestRuns.Asset(Path.Combine("drawings", "hexagons.dxf"));
        var drawing = Core.Jobs.PreparedDrawing.Prepare(new Core.Jobs.JobSpec { ImagePath = path, Size = Core.Geometry.SizeSpec.Width(5) }, new Core.Vectors.VectorOptions());

        var row = RunHistoryRow.From("/logs/d.json", RunRecord.ForDrawing(drawing, "0", TestRuns.Start));

        Assert.Equal(("hexagons.dxf", "drawing"), (row.Source, row.Kind));
        Assert.Null(row.PitchUm);
        Assert.DoesNotContain("µm", row.ProcessText, StringComparison.Ordinal);
        Assert.Contains(",hexagons.dxf,drawing,", RunHistoryRow.ToCsv([row], decimalComma: false), StringComparison.Ordinal);
    }

    [Fact]
    public void ToCsv_DecimalPoint_CommasBetweenFieldsNotesQuoted()
    {
        var lines = RunHistoryRow.ToCsv([Row()], decimalComma: false).Split("\r\n");

        Assert.Equal(string.Join(',', RunHistoryRow.Columns), lines[0]);
        Assert.StartsWith("2026-11-23 14:30:05,S-17,qr-code.bmp,image,", lines[1], StringComparison.Ordinal);
        Assert.Contains(",10.5,7.25,", lines[1], StringComparison.Ordinal);
        Assert.Contains(",failed,61.5,70.3,\"first try\nfocus 2 turns down\",/logs/run.json", RunHistoryRow.ToCsv([Row()], decimalComma: false), StringComparison.Ordinal);
    }

    [Fact]
    public void ToCsv_DecimalComma_SemicolonsBetweenFieldsCommasInNumbers()
    {
        var csv = RunHistoryRow.ToCsv([Row()], decimalComma: true);

        Assert.StartsWith("started;sample ID;image or drawing;", csv, StringComparison.Ordinal);
        Assert.Contains(";10,5;7,25;", csv, StringComparison.Ordinal);
        Assert.Contains(";0,8;1500;", csv, StringComparison.Ordinal);
        Assert.Contains(";failed;61,5;70,3;", csv, StringComparison.Ordinal);
    }

    [Fact]
    public void ToCsv_SampleLikeAFormula_NotTakenAsOne()
    {
        var csv = RunHistoryRow.ToCsv([Row("=HYPERLINK(\"x\")")], decimalComma: false);

        Assert.Contains(",\"'=HYPERLINK(\"\"x\"\")\",", csv, StringComparison.Ordinal);
    }

    [Fact]
    public void ToJson_Rows_AnArrayOfTheSameFields()
    {
        using var json = JsonDocument.Parse(RunHistoryRow.ToJson([Row(), Row("S-18")]));

        var rows = json.RootElement.EnumerateArray().ToList();
        Assert.Equal(2, rows.Count);
        Assert.Equal("S-18", rows[1].GetProperty("sampleId").GetString());
        Assert.Equal(10.5, rows[0].GetProperty("originXMm").GetDouble());
        Assert.Equal("failed", rows[0].GetProperty("outcome").GetString());
        Assert.Equal("/logs/run.json", rows[0].GetProperty("log").GetString());
    }

    [Fact]
    public void Matches_SampleOutcomeOrFile_AnyCase()
    {
        var row = Row();

        Assert.True(row.Matches("s-17"));
        Assert.True(row.Matches("FAILED"));
        Assert.True(row.Matches("qr-code"));
        Assert.True(row.Matches("  "));
        Assert.False(row.Matches("S-99"));
    }
}
