using System.Text.Json;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Marks;

namespace LaserEngrave.Cli.Tests;

/// <summary>`laserengrave mark`: sample IDs into a job of layers, numbered from the counter, proven readable on the twin.</summary>
public sealed class MarkCommandTests : IDisposable
{
    private readonly string _folder = Directory.CreateTempSubdirectory("le-mark-").FullName;

    public void Dispose() => Directory.Delete(_folder, recursive: true);

    private string Counter => Path.Combine(_folder, MarkCounter.FileName);

    private string Out => Path.Combine(_folder, "job");

    [Fact]
    public async Task Mark_TwoDataMatrixIdsChecked_WritesTheJobAndSaysTheyRead()
    {
        var (exit, output, error) = await CliHarness.RunAsync(
            "mark", "S-{n:000}", "--code", "datamatrix", "--size-mm", "1", "--copies", "2", "--out", Out, "--counter", Counter, "--check", "--json");

        Assert.True(exit == 0, error);
        using var json = JsonDocument.Parse(output);
        var root = json.RootElement;
        Assert.Equal(1, root.GetProperty("firstNumber").GetInt32());
        Assert.Equal(["S-001", "S-001", "S-002", "S-002"], root.GetProperty("marks").EnumerateArray().Select(m => m.GetProperty("text").GetString()));
        Assert.All(root.GetProperty("verdicts").EnumerateArray(), v => Assert.True(v.GetProperty("reads").GetBoolean()));
        var layers = JobFile.Load(Path.Combine(Out, MarkLayout.JobFileName));
        Assert.Equal(["Data Matrix \"S-001\"", "text \"S-001\"", "Data Matrix \"S-002\"", "text \"S-002\""], layers.Select(l => l.Name));
        Assert.Equal(1, new MarkCounter(Counter).Next());
    }

    [Fact]
    public async Task Mark_MarksFile_IsReadAsTheOptionsWould()
    {
        var marks = Path.Combine(_folder, "marks.json");
        File.WriteAllText(marks, """{ "text": "{sample}-{n:00}", "code": "qr", "moduleUm": 60, "errorCorrection": "H", "label": false, "copies": 3, "columns": 1 }""");

        var (exit, output, error) = await CliHarness.RunAsync("mark", "--marks", marks, "--sample", "W7", "--start", "5", "--out", Out, "--counter", Counter, "--json");

        Assert.True(exit == 0, error);
        using var json = JsonDocument.Parse(output);
        Assert.Equal(["W7-05", "W7-06", "W7-07"], json.RootElement.GetProperty("marks").EnumerateArray().Select(m => m.GetProperty("text").GetString()));
        Assert.Equal(5, new MarkCounter(Counter).Next());
    }

    [Fact]
    public async Task EngraveJob_OfMarksCompletedOnTheTwin_AdvancesTheCounterAndLogsEveryText()
    {
        var (exit, _, error) = await CliHarness.RunAsync("mark", "ID{n}", "--code", "datamatrix", "--module-um", "40", "--no-label", "--copies", "2", "--out", Out, "--counter", Counter);
        Assert.True(exit == 0, error);
        var logs = Path.Combine(_folder, "logs");

        (exit, var output, error) = await CliHarness.RunAsync("engrave", "--job", Path.Combine(Out, MarkLayout.JobFileName), "--simulate", "--log-dir", logs, "--json");

        Assert.True(exit == 0, error);
        Assert.Contains("the sample counter's next number is 3", error, StringComparison.Ordinal);
        Assert.Equal(3, new MarkCounter(Counter).Next());
        var log = File.ReadAllText(Directory.GetFiles(logs, "*.json").Single(f => !f.Contains("wire", StringComparison.Ordinal)));
        Assert.Contains("Data Matrix \\\"ID1\\\"", log, StringComparison.Ordinal);
        Assert.Contains("Data Matrix \\\"ID2\\\"", log, StringComparison.Ordinal);
    }

    [Fact]
    public async Task EngraveJob_OfMarksAlreadyBurned_RefusedBeforeAnythingMovesSoNoTwoSamplesShareANumber()
    {
        var (exit, _, error) = await CliHarness.RunAsync("mark", "ID{n}", "--code", "datamatrix", "--module-um", "40", "--no-label", "--out", Out, "--counter", Counter);
        Assert.True(exit == 0, error);
        // A second job made from the same counter before the first burned: the same number.
        var other = Path.Combine(_folder, "other");
        (exit, _, error) = await CliHarness.RunAsync("mark", "ID{n}", "--code", "datamatrix", "--module-um", "40", "--no-label", "--out", other, "--counter", Counter);
        Assert.True(exit == 0, error);
        var logs = Path.Combine(_folder, "logs");
        var job = Path.Combine(Out, MarkLayout.JobFileName);
        (exit, _, error) = await CliHarness.RunAsync("engrave", "--job", job, "--simulate", "--log-dir", logs);
        Assert.True(exit == 0, error);

        var again = await CliHarness.RunAsync("engrave", "--job", job, "--simulate", "--log-dir", logs);
        var twin = await CliHarness.RunAsync("engrave", "--job", Path.Combine(other, MarkLayout.JobFileName), "--simulate", "--log-dir", logs);

        foreach (var (code, output, message) in new[] { again, twin })
        {
            Assert.Equal(2, code);
            Assert.Empty(output);
            Assert.Contains("its marks carry the numbers 1..1, which a completed run has burned already", message, StringComparison.Ordinal);
            Assert.Single(message.TrimEnd().Split('\n'));
        }

        Assert.Single(Directory.GetFiles(logs, "*.json"), f => !f.Contains("wire", StringComparison.Ordinal));
        Assert.Equal(2, new MarkCounter(Counter).Next());
    }

    [Fact]
    public async Task Mark_CodeThatDoesNotReadWhereAJobWasMade_RefusesAndLeavesNoJobToBurn()
    {
        var (exit, _, error) = await CliHarness.RunAsync("mark", "S-{n:000}", "--code", "datamatrix", "--module-um", "60", "--out", Out, "--counter", Counter, "--check");
        Assert.True(exit == 0, error);
        Assert.True(File.Exists(Path.Combine(Out, MarkLayout.JobFileName)));

        (exit, var output, error) = await CliHarness.RunAsync("mark", "S-{n:000}", "--code", "datamatrix", "--module-um", "20", "--out", Out, "--counter", Counter, "--check");

        Assert.Equal(2, exit);
        Assert.Contains("does NOT read", output, StringComparison.Ordinal);
        Assert.Contains("\"S-001\" does not read on the twin (124 of 144 modules right", error, StringComparison.Ordinal);
        Assert.False(File.Exists(Path.Combine(Out, MarkLayout.JobFileName)), "the earlier job was taken away");
        Assert.False(File.Exists(Path.Combine(Out, MarkLayout.ManifestFileName)));
    }

    [Theory]
    [InlineData("mark|S|--code|datamatrix|--size-mm|0.15|--out|@out", "smaller than the spot's 20 µm diameter")]
    [InlineData("mark|S|--code|datamatrix|--out|@out", "one of the two")]
    [InlineData("mark|S|--code|aztec|--size-mm|2|--out|@out", "--code aztec: not qr, datamatrix or none")]
    [InlineData("mark|S-{x}|--out|@out", "unknown placeholder {x}")]
    [InlineData("mark|{sample}|--out|@out", "needs the run's sample ID")]
    [InlineData("mark|S|--copies|0|--out|@out", "copies 0")]
    [InlineData("mark|S|--copies|1000|--out|@out", "copies 1000")]
    [InlineData("mark|S|--code|qr|--ecc|Z|--module-um|50|--out|@out", "not L, M, Q or H")]
    [InlineData("mark|S|--code|datamatrix|--ecc|H|--module-um|50|--out|@out", "for QR codes")]
    [InlineData("mark|S|--text-height-mm|NaN|--out|@out", "--text-height-mm NaN")]
    [InlineData("mark|S|--align|middle|--out|@out", "--align middle")]
    [InlineData("mark|Süß|--out|@out", "the engraving font has no 'ü'")]
    [InlineData("mark|S|--font|No Such Font|--out|@out", "\"No Such Font\" is not installed")]
    [InlineData("mark|S|--origin-mm|59,59|--copies|10|--out|@out", "copy 2 of 10 (number 2, \"S\") would reach 60.762 mm in X, past the stage's travel 0..60 mm (--origin-mm 59, 59): move --origin-mm to at most 47.19 mm in X, or give fewer --columns or a smaller --pitch-mm")]
    [InlineData("mark|S-{n}|--origin-mm|10,58|--copies|12|--columns|4|--pitch-mm|2,2|--out|@out", "(number 5, \"S-5\") would reach 60.4 mm in Y")]
    [InlineData("mark|S-{n}|--origin-mm|10,58|--copies|12|--columns|4|--pitch-mm|2,2|--out|@out", "give fewer --copies (or more --columns) or a smaller --pitch-mm")]
    [InlineData("mark|S|--origin-mm|59.9,10|--out|@out", "the mark \"S\" would reach")]
    [InlineData("mark|S|--copies|3|--pitch-mm|0.0001,1|--out|@out", "--pitch-mm X 0.0001 mm is less than a copy's width, 0.381 mm: the copies would burn over each other")]
    [InlineData("mark|S|--copies|30|--columns|3|--pitch-mm|1,0.1|--out|@out", "--pitch-mm Y 0.1 mm is less than a copy's height")]
    [InlineData("mark|S|--code|qr|--size-mm|70|--out|@out", "the mark is 96.667 mm in X, more than the stage's travel 0..60 mm: make it smaller (--size-mm or --module-um)")]
    [InlineData("mark|S|--code|qr|--size-mm|30|--copies|2|--out|@out", "the array is 83.857 mm in X, more than the travel: give fewer --columns or a smaller --pitch-mm")]
    [InlineData("mark|S|--origin-mm|1e308,5|--out|@out", "would reach 1E+308 mm in X")]
    [InlineData("mark|S|--speed-mm-s|99|--out|@out", "--speed-mm-s 99: outside what the stage takes")]
    [InlineData("mark|S|--passes|0|--out|@out", "--passes 0: must be 1..")]
    [InlineData("mark|S|--code|qr|--size-mm|200|--out|@out", "--size-mm 200 must be above 0")]
    [InlineData("mark|S|--code|qr|--out|@out", "its module size (--module-um, µm) or its size (--size-mm, mm)")]
    [InlineData("mark|S|--pitch-mm|4|--out|@out", "--pitch-mm 4")]
    [InlineData("mark|--out|@out", "give the mark's TEXT")]
    [InlineData("mark|S|--smallest|--out|@out", "--smallest needs --check")]
    [InlineData("mark|S|--start|0|--out|@out", "counter 0")]
    [InlineData("mark|--marks|@missing|--out|@out", "missing.json: no such file")]
    [InlineData("mark|--marks|@bad|--out|@out", "unknown field \"colour\"")]
    [InlineData("mark|--marks|@far|--out|@out", "far.json: the mark \"S\" would reach 60.381 mm in X, past the stage's travel 0..60 mm (originMm 60, 10): move originMm to at most 59.619 mm in X")]
    [InlineData("mark|S|--marks|@bad|--out|@out", "not both")]
    [InlineData("mark|S|--out|/proc/no-such/marks", "the marks' folder cannot be made there")]
    [InlineData("mark|S|--counter|@folder|--out|@out", "is a folder, not the sample counter's file")]
    public async Task Mark_BadInput_OneLineExitTwoNothingWritten(string line, string fragment)
    {
        File.WriteAllText(Path.Combine(_folder, "bad.json"), """{ "text": "S", "colour": "red" }""");
        File.WriteAllText(Path.Combine(_folder, "far.json"), """{ "text": "S", "originMm": [60, 10] }""");
        var args = line.Split('|').Select(a => a switch
        {
            "@out" => Out,
            "@missing" => Path.Combine(_folder, "missing.json"),
            "@bad" => Path.Combine(_folder, "bad.json"),
            "@far" => Path.Combine(_folder, "far.json"),
            "@folder" => _folder,
            _ => a,
        }).ToList();
        if (!args.Contains("--counter"))
        {
            args.AddRange(["--counter", Counter]);
        }


        var (exit, output, error) = await CliHarness.RunAsync([.. args]);

        Assert.True(exit == 2, $"exit {exit}: {error}");
        Assert.Single(error.TrimEnd().Split('\n'));
        Assert.Contains(fragment, error, StringComparison.Ordinal);
        Assert.Equal(string.Empty, output);
        Assert.False(File.Exists(Path.Combine(Out, MarkLayout.JobFileName)), "no job was written");
    }

    [Fact]
    public async Task Mark_StartWithARefusedMark_LeavesTheCounterUnwritten()
    {
        var file = Path.Combine(_folder, "a-file");
        File.WriteAllText(file, "x");

        var (exit, _, error) = await CliHarness.RunAsync("mark", "S-{n}", "--start", "7", "--out", file, "--counter", Counter);

        Assert.True(exit == 2, $"exit {exit}: {error}");
        Assert.Contains("is a file", error, StringComparison.Ordinal);
        Assert.False(File.Exists(Counter), "the counter was written for a refused mark");
    }
}
